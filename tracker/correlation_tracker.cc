#include "tracker/correlation_tracker.h"

#include <map>
#include <opencv2/imgproc.hpp>
#include <optional>

#include "pyramid/segmentation.h"
#include "tracker/correlation_target.h"
#include "util/error.h"
#include "util/timer.h"

namespace attend {

namespace {

using tracker_internal::CorrelationTarget;

class CorrelationTargetTracker final : public TargetTracker {
 public:
  CorrelationTargetTracker(const CorrelationOptions& options, BipPool* pool)
      : options_(options), pool_(pool) {}

  int StartFromBox(const cv::Mat& frame, const cv::Rect& box, TrackSimilarity,
                   const cv::Mat&) override {
    return Start(frame, box & cv::Rect(0, 0, frame.cols, frame.rows));
  }

  int StartFromMask(const cv::Mat& frame, const cv::Mat& mask, TrackSimilarity,
                    const cv::Mat&) override {
    ATTEND_CHECK(mask.type() == CV_8UC1 && mask.size() == frame.size())
        << "mask must be CV_8UC1 of the frame's size";
    return Start(frame, cv::boundingRect(mask));
  }

  void Track(const cv::Mat& frame, std::vector<TrackResult>* results, const cv::Mat&,
             const cv::Mat&) override {
    ATTEND_CHECK(frame.type() == CV_8UC3) << "frames must be 8-bit BGR";
    const Stopwatch stopwatch;
    std::vector<int> lost;
    for (auto& [id, entry] : targets_) {
      const cv::Rect search_box = entry.target.box();
      TrackResult result;
      result.id = id;
      result.state = entry.target.Track(frame);
      result.box = entry.target.box();
      result.centroid = cv::Point2f(static_cast<float>(entry.target.centre().x),
                                    static_cast<float>(entry.target.centre().y));
      result.overlap = entry.target.peak();
      result.roi = search_box;
      entry.mask.release();
      if (result.state == TrackState::kFound) {
        result.level = 0;
        result.area = result.box.area();
        entry.crop = frame(result.box).clone();
        entry.frame_size = frame.size();
      } else {
        entry.crop.release();
      }
      if (result.state == TrackState::kLost) lost.push_back(id);
      results->push_back(result);
    }
    for (const int id : lost) targets_.erase(id);
    milliseconds_ = stopwatch.ElapsedMs();
  }

  cv::Mat Mask(int id) const override {
    const auto it = targets_.find(id);
    if (it == targets_.end() || it->second.crop.empty()) return cv::Mat();
    const Entry& entry = it->second;
    if (entry.mask.empty()) entry.mask = TargetMask(entry);
    return entry.mask;
  }
  void Remove(int id) override { targets_.erase(id); }
  std::vector<int> ids() const override {
    std::vector<int> result;
    for (const auto& [id, entry] : targets_) result.push_back(id);
    return result;
  }
  TrackerKind kind() const override { return TrackerKind::kBip; }
  double milliseconds() const override { return milliseconds_; }

 private:
  // A target, and what its mask is made from: the box's pixels in the last frame it was found
  // in (empty when it was not). The mask is made when asked for (Mask), so that a caller
  // that needs only boxes does not pay for the segmentation, and kept until the next frame.
  struct Entry {
    CorrelationTarget target;
    cv::Mat crop;
    cv::Size frame_size;
    mutable cv::Mat mask;  // frame size; a cache of TargetMask
  };

  int Start(const cv::Mat& frame, const cv::Rect& box) {
    ATTEND_CHECK(frame.type() == CV_8UC3) << "frames must be 8-bit BGR";
    if (box.width < 2 || box.height < 2) return -1;
    Entry entry{CorrelationTarget(options_, frame, box), cv::Mat(), frame.size(), cv::Mat()};
    entry.crop = frame(entry.target.box()).clone();
    const int id = next_id_++;
    targets_.emplace(id, std::move(entry));
    return id;
  }

  // The regions of the box's BIP over-segmentation whose mean colour likelihood reaches
  // mask_likelihood; the whole box when that is 0 or no region does.
  cv::Mat TargetMask(const Entry& entry) const {
    cv::Mat mask(entry.frame_size, CV_8UC1, cv::Scalar(0));
    const cv::Rect box = entry.target.box();
    if (options_.mask_likelihood <= 0.f) {
      mask(box).setTo(255);
      return mask;
    }
    if (!segmenter_) segmenter_.emplace(SegmentationOptions(), pool_);
    const cv::Mat& crop = entry.crop;
    Segmentation segmentation;
    segmenter_->Segment(crop, &segmentation);
    segmenter_->ReleasePyramid();
    const cv::Mat likelihood = entry.target.Likelihood(crop);
    const int regions = static_cast<int>(segmentation.regions.size());
    std::vector<double> sum(regions, 0.0);
    std::vector<int> count(regions, 0);
    for (int r = 0; r < crop.rows; ++r) {
      const int* labels = segmentation.labels.ptr<int>(r);
      const float* values = likelihood.ptr<float>(r);
      for (int c = 0; c < crop.cols; ++c) {
        if (labels[c] < 0 || labels[c] >= regions) continue;
        sum[labels[c]] += values[c];
        ++count[labels[c]];
      }
    }
    cv::Mat inside = mask(box);
    for (int r = 0; r < crop.rows; ++r) {
      const int* labels = segmentation.labels.ptr<int>(r);
      uchar* out = inside.ptr<uchar>(r);
      for (int c = 0; c < crop.cols; ++c) {
        const int label = labels[c];
        if (label >= 0 && label < regions && sum[label] >= options_.mask_likelihood * count[label]) {
          out[c] = 255;
        }
      }
    }
    if (cv::countNonZero(inside) == 0) inside.setTo(255);
    return mask;
  }

  CorrelationOptions options_;
  BipPool* pool_;
  mutable std::optional<Segmenter> segmenter_;  // made for the first mask
  std::map<int, Entry> targets_;
  int next_id_ = 1;
  double milliseconds_ = 0.0;
};

}  // namespace

std::unique_ptr<TargetTracker> MakeCorrelationTracker(const CorrelationOptions& options,
                                                      BipPool* pool) {
  return std::make_unique<CorrelationTargetTracker>(options, pool);
}

}  // namespace attend
