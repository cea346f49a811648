// MultiTracker (tracker/tracker.h): the targets, the pyramid over their regions of interest
// (roi_pyramid.h) and the starts; how a target is searched for, found and missed is its mode's
// (tracker_mode.h: thesis_mode.cc, bounded_mode.cc).
#include "tracker/tracker.h"

#include <algorithm>
#include <opencv2/imgproc.hpp>

#include "pyramid/segmentation.h"
#include "tracker/refinement.h"
#include "tracker/roi_pyramid.h"
#include "tracker/target.h"
#include "tracker/template_update.h"
#include "tracker/tracker_mode.h"
#include "util/error.h"
#include "util/timer.h"

namespace attend {

using namespace tracker_internal;

namespace {

std::unique_ptr<ModePolicy> MakeMode(const TrackerOptions& options) {
  switch (options.mode) {
    case TrackerMode::kThesis:
      return MakeThesisMode(options);
    case TrackerMode::kBounded:
      return MakeBoundedMode(options);
    case TrackerMode::kCorrelation:
      break;
  }
  // The correlation mode is not a MultiTracker policy: TargetTracker::Create makes it.
  throw ConfigError("tracker.mode correlation is a tracker of its own: make it with "
                    "TargetTracker::Create, not MultiTracker");
}

}  // namespace

struct MultiTracker::Impl {
  Impl(const TrackerOptions& o, BipPool* p)
      : options(o),
        mode(MakeMode(o)),
        own_pool(p == nullptr ? std::make_unique<BipPool>() : nullptr),
        pool(p != nullptr ? p : own_pool.get()),
        pyramids(pool),
        segmenter(SegmentationOptions{}, pool) {}

  // Searches every target of each similarity in its part of that similarity's pyramid.
  void Track(const cv::Mat& frame, const cv::Mat& skin, const cv::Mat& cylinder,
             std::vector<TrackResult>* results);
  int Start(const cv::Mat& frame, const cv::Mat& skin, TrackSimilarity similarity,
            const cv::Mat& target_mask, const cv::Mat& build_mask);

  TrackerOptions options;
  std::unique_ptr<ModePolicy> mode;
  std::unique_ptr<BipPool> own_pool;  // when the tracker was given none
  BipPool* pool;                      // of the pyramids and the segmenter
  std::vector<Target> targets;
  int next_id = 1;
  RoiPyramids pyramids;
  double segmentation_ms = 0.0;  // of the last Track()
  Segmenter segmenter;           // chooses a target's regions in a box (thesis 4.2.1)
  std::vector<cv::Rect> rois;    // per target, Track's buffer
};

void MultiTracker::Impl::Track(const cv::Mat& frame, const cv::Mat& skin, const cv::Mat& cylinder,
                               std::vector<TrackResult>* results) {
  segmentation_ms = 0.0;
  const TrackFrame track_frame = mode->Frame(frame, cylinder);
  const cv::Rect image(0, 0, frame.cols, frame.rows);
  for (const TrackSimilarity similarity : {TrackSimilarity::kColour, TrackSimilarity::kSkin}) {
    // The ROIs of this similarity's targets: their box and border, in the image (4.2.6).
    rois.assign(targets.size(), cv::Rect());
    for (size_t i = 0; i < targets.size(); ++i) {
      Target& target = targets[i];
      if (target.similarity != similarity) continue;
      target.roi =
          cv::Rect(target.box.x - target.border, target.box.y - target.border,
                   target.box.width + 2 * target.border, target.box.height + 2 * target.border) &
          image;
      rois[i] = target.roi;
    }
    const int pyramid_levels =
        pyramids.Build(frame, skin, cylinder, similarity, rois, options.t_oversegment,
                       options.pyramid_parts, &segmentation_ms);
    if (pyramid_levels == 0) continue;
    for (size_t i = 0; i < targets.size(); ++i) {
      Target& target = targets[i];
      if (target.similarity != similarity) continue;
      TrackResult result;
      result.id = target.id;
      result.roi = target.roi;
      mode->Track(track_frame, pyramids.PartOf(similarity, i), pyramid_levels, &target, &result);
      result.box = target.box;
      result.centroid = target.centroid;
      results->push_back(result);
    }
  }
  std::sort(results->begin(), results->end(),
            [](const TrackResult& a, const TrackResult& b) { return a.id < b.id; });
  pyramids.Release();
  targets.erase(std::remove_if(targets.begin(), targets.end(),
                               [](const Target& t) { return t.levels.empty(); }),
                targets.end());
}

int MultiTracker::Impl::Start(const cv::Mat& frame, const cv::Mat& skin, TrackSimilarity similarity,
                              const cv::Mat& target_mask, const cv::Mat& build_mask) {
  if (cv::countNonZero(target_mask) == 0) return -1;
  Hierarchy& h = pyramids.Pyramid(similarity, 0);
  const cv::Rect built = cv::boundingRect(build_mask);
  BuildHierarchy(frame, skin, similarity, build_mask, built, 0, options.t_oversegment, &h);
  // The target's regions: those with most of their pixels in `target_mask`.
  std::vector<int> inside(h.regions, 0), all(h.regions, 0);
  const BipLevel& base = h.bip->level(0);
  for (int y = 0; y < h.size.height; ++y) {
    const uchar* m = target_mask.ptr<uchar>(y + h.origin.y) + h.origin.x;
    for (int x = 0; x < h.size.width; ++x) {
      const int cell = y * base.cols + x;
      if (!base.hom[cell] || h.region[0][cell] < 0) continue;
      ++all[h.region[0][cell]];
      if (m[x]) ++inside[h.region[0][cell]];
    }
  }
  std::vector<uint8_t> in_target(h.regions, 0);
  for (int r = 0; r < h.regions; ++r) in_target[r] = 2 * inside[r] > all[r];
  Target target;
  target.similarity = similarity;
  const cv::Rect keep = mode->StartBounds(target_mask, frame.size());
  PaintTarget(h, in_target, keep, frame.size(), &target.mask);
  if (cv::countNonZero(target.mask) == 0) {
    h.Release();
    return -1;
  }
  target.levels = MakeTemplate(h, in_target, keep, nullptr, {}, h.bip->num_levels(), options.alpha);
  if (target.levels.empty()) {
    h.Release();
    return -1;
  }
  const cv::Moments moments = cv::moments(target.mask, true);
  target.box = cv::boundingRect(target.mask);
  target.centroid = {static_cast<float>(moments.m10 / moments.m00),
                     static_cast<float>(moments.m01 / moments.m00)};
  target.border = options.EpsilonPixels(frame.cols);
  mode->Start(frame, h, built, &target);
  h.Release();
  target.id = next_id++;
  targets.push_back(std::move(target));
  return targets.back().id;
}

MultiTracker::MultiTracker(TrackerOptions options, BipPool* pool)
    : options_(options), impl_(std::make_unique<Impl>(options, pool)) {
  const std::string error = options_.Check();
  if (!error.empty()) throw ConfigError("tracker: " + error);
}

MultiTracker::~MultiTracker() = default;

namespace {

void CheckFrame(const cv::Mat& frame, TrackSimilarity similarity, const cv::Mat& skin) {
  ATTEND_CHECK(!frame.empty() && frame.type() == CV_8UC3) << "frames must be 8-bit BGR";
  if (similarity == TrackSimilarity::kSkin) {
    ATTEND_CHECK(skin.type() == CV_8UC1 && skin.size() == frame.size())
        << "skin targets need the frame's binary skin map";
  }
}

}  // namespace

int MultiTracker::StartFromMask(const cv::Mat& frame, const cv::Mat& mask,
                                TrackSimilarity similarity, const cv::Mat& skin) {
  CheckFrame(frame, similarity, skin);
  ATTEND_CHECK(mask.type() == CV_8UC1 && mask.size() == frame.size())
      << "a target mask must be CV_8UC1 of the frame's size";
  // Over-segment the mask's box plus the ROI border, so that regions can be judged by how much
  // of them lies in the mask.
  const int border = options_.EpsilonPixels(frame.cols);
  const cv::Rect box = cv::boundingRect(mask);
  if (box.empty()) return -1;
  cv::Mat build(frame.size(), CV_8UC1, cv::Scalar(0));
  build(cv::Rect(box.x - border, box.y - border, box.width + 2 * border, box.height + 2 * border) &
        cv::Rect(0, 0, frame.cols, frame.rows))
      .setTo(255);
  return impl_->Start(frame, skin, similarity, mask, build);
}

int MultiTracker::StartFromBox(const cv::Mat& frame, const cv::Rect& box,
                               TrackSimilarity similarity, const cv::Mat& skin) {
  CheckFrame(frame, similarity, skin);
  const cv::Rect image(0, 0, frame.cols, frame.rows);
  const cv::Rect inside = box & image;
  if (inside.empty()) return -1;
  cv::Mat mask(frame.size(), CV_8UC1, cv::Scalar(0));
  if (impl_->mode->BoxIsTarget() && similarity == TrackSimilarity::kColour) {
    mask(inside).setTo(255);
    const int id = StartFromMask(frame, mask, similarity, skin);
    if (id >= 0) impl_->targets.back().box = inside;
    return id;
  }
  if (similarity == TrackSimilarity::kSkin) {
    mask(inside).setTo(255, skin(inside));
    return StartFromMask(frame, mask, similarity, skin);
  }
  // The target is what the colour segmentation (thesis 4.2.1, chapter 3) finds mostly inside
  // the box. The box's surroundings, as wide as the box, are segmented with it, so that the
  // background in the box's corners joins the background outside and stays out.
  const cv::Rect context = cv::Rect(inside.x - inside.width, inside.y - inside.height,
                                    3 * inside.width, 3 * inside.height) &
                           image;
  Segmentation segmentation;
  impl_->segmenter.Segment(frame(context), &segmentation);
  impl_->segmenter.ReleasePyramid();
  const cv::Rect local = inside - context.tl();
  std::vector<int> within(segmentation.regions.size(), 0);
  for (int y = local.y; y < local.y + local.height; ++y) {
    const int* label = segmentation.labels.ptr<int>(y);
    for (int x = local.x; x < local.x + local.width; ++x) {
      if (label[x] >= 0) ++within[label[x]];
    }
  }
  for (int y = 0; y < context.height; ++y) {
    const int* label = segmentation.labels.ptr<int>(y);
    uchar* out = mask.ptr<uchar>(y + context.y) + context.x;
    for (int x = 0; x < context.width; ++x) {
      if (label[x] >= 0 && 2 * within[label[x]] > segmentation.regions[label[x]].area) out[x] = 255;
    }
  }
  return StartFromMask(frame, mask, similarity, skin);
}

int MultiTracker::StartFromRegion(const cv::Mat& frame, const cv::Mat& labels, int region,
                                  TrackSimilarity similarity, const cv::Mat& skin) {
  CheckFrame(frame, similarity, skin);
  ATTEND_CHECK(labels.type() == CV_32SC1 && labels.size() == frame.size())
      << "segmentation labels must be CV_32SC1 of the frame's size";
  if (region < 0) return -1;
  return StartFromMask(frame, labels == region, similarity, skin);
}

void MultiTracker::Track(const cv::Mat& frame, std::vector<TrackResult>* results,
                         const cv::Mat& skin, const cv::Mat& cylinder) {
  const Stopwatch stopwatch;
  ATTEND_CHECK(!frame.empty() && frame.type() == CV_8UC3) << "frames must be 8-bit BGR";
  ATTEND_CHECK(cylinder.empty() || (cylinder.type() == CV_32FC3 && cylinder.size() == frame.size()))
      << "the cylinder image must be CV_32FC3 of the frame's size";
  std::vector<TrackResult> found;
  impl_->Track(frame, skin, cylinder, &found);
  results->insert(results->end(), found.begin(), found.end());
  milliseconds_ = stopwatch.ElapsedMs();
  segmentation_milliseconds_ = impl_->segmentation_ms;
}

cv::Mat MultiTracker::Mask(int id) const {
  for (const Target& target : impl_->targets) {
    if (target.id == id) return target.mask;
  }
  return cv::Mat();
}

cv::Mat MultiTracker::TemplateWeights(int id, int level) const {
  for (const Target& target : impl_->targets) {
    if (target.id != id) continue;
    if (level < 0 || level >= static_cast<int>(target.levels.size())) return cv::Mat();
    const TemplateLevel& t = target.levels[level];
    return cv::Mat(t.cells.height, t.cells.width, CV_32FC1, const_cast<float*>(t.weight.data()))
        .clone();
  }
  return cv::Mat();
}

void MultiTracker::Remove(int id) {
  auto& targets = impl_->targets;
  targets.erase(
      std::remove_if(targets.begin(), targets.end(), [id](const Target& t) { return t.id == id; }),
      targets.end());
}

std::vector<int> MultiTracker::ids() const {
  std::vector<int> ids;
  for (const Target& target : impl_->targets) ids.push_back(target.id);
  return ids;
}

}  // namespace attend
