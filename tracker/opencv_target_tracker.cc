// The kcf and csrt kinds of TargetTracker: one OpenCV tracker (contrib's tracking module) per
// target.
#include <map>
#include <memory>
#include <opencv2/imgproc.hpp>

#include "tracker/tracker_kinds.h"
#include "util/error.h"
#include "util/opencv_extra.h"
#include "util/timer.h"

namespace attend {

namespace {

class OpenCvTargetTracker final : public TargetTracker {
 public:
  // Loads the optional OpenCV module (util/opencv_extra.h) at once, so that a missing one is
  // reported before the run starts.
  OpenCvTargetTracker(TrackerKind kind, cvextra::TrackerType type,
                      const OpenCvTrackerOptions& options)
      : kind_(kind),
        type_(type),
        options_(options),
        opencv_(&cvextra::Get(std::string("tracker.kind ") + TrackerKindName(kind))) {}

  int StartFromBox(const cv::Mat& frame, const cv::Rect& box, TrackSimilarity,
                   const cv::Mat&) override {
    const cv::Rect inside = box & cv::Rect(0, 0, frame.cols, frame.rows);
    if (inside.empty()) return -1;
    return Start(frame, inside, cv::Mat(inside.size(), CV_8UC1, cv::Scalar(255)));
  }

  int StartFromMask(const cv::Mat& frame, const cv::Mat& mask, TrackSimilarity,
                    const cv::Mat&) override {
    ATTEND_CHECK(mask.type() == CV_8UC1 && mask.size() == frame.size())
        << "mask must be CV_8UC1 of the frame's size";
    const cv::Rect box = cv::boundingRect(mask);
    if (box.empty()) return -1;
    cv::Mat shape = mask(box) != 0;
    return Start(frame, box, shape);
  }

  void Track(const cv::Mat& frame, std::vector<TrackResult>* results, const cv::Mat&,
             const cv::Mat&) override {
    const Stopwatch stopwatch;
    const cv::Rect image(0, 0, frame.cols, frame.rows);
    std::vector<int> lost;
    for (auto& [id, target] : targets_) {
      cv::Rect box = target.box;
      bool found = false;
      try {
        found = target.tracker->Update(frame, &box);
      } catch (const cv::Exception&) {
        found = false;  // OpenCV refuses a degenerate window: a failure like any other
      }
      box &= image;
      found = found && !box.empty();
      TrackResult result;
      result.id = id;
      if (found) {
        target.box = box;
        target.failures = 0;
        target.mask = ShapeMask(target.shape, box, frame.size());
        result.state = TrackState::kFound;
        result.area = cv::countNonZero(target.mask);
      } else {
        target.mask.release();
        ++target.failures;
        result.state =
            target.failures >= options_.lost_frames ? TrackState::kLost : TrackState::kOccluded;
        if (result.state == TrackState::kLost) lost.push_back(id);
      }
      result.box = target.box;
      result.roi = target.box;
      result.centroid = cv::Point2f(target.box.x + 0.5f * target.box.width,
                                    target.box.y + 0.5f * target.box.height);
      results->push_back(result);
    }
    for (const int id : lost) targets_.erase(id);
    milliseconds_ = stopwatch.ElapsedMs();
  }

  cv::Mat Mask(int id) const override {
    const auto it = targets_.find(id);
    return it == targets_.end() ? cv::Mat() : it->second.mask;
  }
  void Remove(int id) override { targets_.erase(id); }
  std::vector<int> ids() const override {
    std::vector<int> result;
    for (const auto& [id, target] : targets_) result.push_back(id);
    return result;
  }
  TrackerKind kind() const override { return kind_; }
  double milliseconds() const override { return milliseconds_; }

 private:
  struct Target {
    std::unique_ptr<cvextra::Tracker> tracker;
    cv::Rect box;      // the last box found
    cv::Mat shape;     // CV_8UC1 of the start box's size: the target's start shape
    cv::Mat mask;      // frame size; empty when not found in the last frame
    int failures = 0;  // failed updates in a row
  };

  std::unique_ptr<cvextra::Tracker> MakeTracker() const {
    return opencv_->CreateTracker(type_, options_.kcf_detect_thresh);
  }

  // The start shape resized to `box` and placed there, in a mask of `size`.
  static cv::Mat ShapeMask(const cv::Mat& shape, const cv::Rect& box, const cv::Size& size) {
    cv::Mat mask(size, CV_8UC1, cv::Scalar(0));
    cv::Mat inside = mask(box);
    cv::resize(shape, inside, box.size(), 0, 0, cv::INTER_NEAREST);
    return mask;
  }

  int Start(const cv::Mat& frame, const cv::Rect& box, const cv::Mat& shape) {
    ATTEND_CHECK(frame.type() == CV_8UC3) << "frames must be 8-bit BGR";
    Target target;
    target.tracker = MakeTracker();
    try {
      target.tracker->Init(frame, box);
    } catch (const cv::Exception&) {
      return -1;  // a box too small for the tracker's features
    }
    target.box = box;
    target.shape = shape;
    target.mask = ShapeMask(shape, box, frame.size());
    const int id = next_id_++;
    targets_.emplace(id, std::move(target));
    return id;
  }

  TrackerKind kind_;
  cvextra::TrackerType type_;
  OpenCvTrackerOptions options_;
  cvextra::Module* opencv_;
  std::map<int, Target> targets_;
  int next_id_ = 1;
  double milliseconds_ = 0.0;
};

bool UsesKcfKey(std::string_view key) { return HasKey(OpenCvTrackerOptions::Fields(), key); }
bool UsesCsrtKey(std::string_view key) { return key == "lost_frames"; }

std::string CheckOpenCv(const TargetTrackerOptions& options) { return options.opencv.Check(); }

std::vector<TrackerSetting> NoSettings(const TargetTrackerOptions&) { return {}; }

// The OpenCV kinds build no pyramid: they take no pool.
std::unique_ptr<TargetTracker> CreateKcf(const TargetTrackerOptions& options, BipPool*) {
  return std::make_unique<OpenCvTargetTracker>(TrackerKind::kKcf, cvextra::TrackerType::kKcf,
                                               options.opencv);
}

std::unique_ptr<TargetTracker> CreateCsrt(const TargetTrackerOptions& options, BipPool*) {
  return std::make_unique<OpenCvTargetTracker>(TrackerKind::kCsrt, cvextra::TrackerType::kCsrt,
                                               options.opencv);
}

}  // namespace

const TrackerKindInfo& KcfKind() {
  static const TrackerKindInfo row = {.kind = TrackerKind::kKcf,
                                      .name = "kcf",
                                      .colour_similarity = "appearance",
                                      .skin_similarity = "appearance",
                                      .uses_key = &UsesKcfKey,
                                      .check = &CheckOpenCv,
                                      .config_file = nullptr,
                                      .no_target = nullptr,
                                      .settings = &NoSettings,
                                      .create = &CreateKcf};
  return row;
}

const TrackerKindInfo& CsrtKind() {
  static const TrackerKindInfo row = {.kind = TrackerKind::kCsrt,
                                      .name = "csrt",
                                      .colour_similarity = "appearance",
                                      .skin_similarity = "appearance",
                                      .uses_key = &UsesCsrtKey,
                                      .check = &CheckOpenCv,
                                      .config_file = nullptr,
                                      .no_target = nullptr,
                                      .settings = &NoSettings,
                                      .create = &CreateCsrt};
  return row;
}

}  // namespace attend
