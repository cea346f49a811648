// The semi-attentive stage and inhibition of return (thesis 5.1.2, 5.1.3; SPEC 1, 2.4).
//
// Every frame, after the trackers have searched for the targets already attended and the
// saliency map is made:
//   inhibition = the union of the tracked targets' masks, dilated by `inhibition.margin`
//                (occluded targets keep inhibiting their last box while keep_occluded);
//   inhibited  = saliency * (1 - inhibition);
//   the inhibited saliency is segmented into regions of homogeneous saliency (a BIP over the
//   saliency map); regions with mean saliency >= select.min_saliency and area >=
//   select.min_area are candidates, ranked by mean saliency times area; each candidate becomes
//   the colour region of the frame's segmentation that it overlaps most, unless that region
//   overlaps an active target (its mask, or its box while occluded) or is larger than
//   select.max_area_fraction of the image; at most
//   select.max_new targets start a frame, select.max_targets are active at once. A region that
//   is mostly skin starts a skin-similarity tracker.
// Lifecycle: new (the frame it starts) -> tracked (found) / occluded (not found) -> lost (its
// template forgotten, or for the OpenCV kinds tracker.lost_frames failures in a row). A found
// target is released, and inhibits nothing from that frame on, when its mask covers more than
// select.max_area_fraction of the image ("too_large"), when its box spans the image: at least
// 0.9 of its width and 0.9 of its height ("spans_image"), when its box holds fewer than
// select.min_area pixels ("too_small"), when its own uninhibited saliency
// (mean over its mask) stays below drop.min_saliency for drop.frames frames in a row
// ("low_saliency"), or when more than drop.max_shared of its mask is held by older targets
// found and kept this frame ("duplicate"); the first rule that holds is the reason recorded.
// Each step is a unit of its own under semiattentive/ (README.md there): candidates.h, seeds.h,
// motion_grouping.h, recognition.h, release.h, inhibition.h, object_files.h; the targets
// followed across frames are followed_targets.h's.
#pragma once

#include <limits>
#include <memory>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "colour/skin_model.h"
#include "features/feature_map.h"
#include "io/target_state.h"
#include "pyramid/segmentation.h"
#include "semiattentive/attention_options.h"
#include "semiattentive/object_files.h"
#include "semiattentive/target_depth.h"
#include "tracker/target_tracker.h"

namespace attend {

// One target in one frame (SPEC 3.3).
struct AttendedTarget {
  int id = 0;
  cv::Rect box;
  int area = 0;
  double saliency = 0.0;  // mean uninhibited saliency over its mask (or its box when hidden)
  TargetState state = TargetState::kNew;
  // Why a released target was released (kNone in every other state).
  ReleaseReason reason = ReleaseReason::kNone;
  bool skin = false;
  int absent_frames = 0;  // state resumed: the frames its object file was remembered unseen
  std::string label;      // from a top-down channel's detections; "" when none
  // A stereo run with depth.method set, a target seen this frame (new, tracked, resumed):
  // its disparity, filtered over its frames, and its standard deviation, working pixels
  // (NaN when it has none), and its mask's centroid.
  double disparity = std::numeric_limits<double>::quiet_NaN();
  double disparity_sd = std::numeric_limits<double>::quiet_NaN();
  bool depth_unmeasured = false;  // no disparity: too few of its pixels measured
  cv::Point2f centroid{-1.f, -1.f};
};

struct AttentionFrame {
  std::vector<AttendedTarget> targets;
  std::vector<int> new_ids;
  double inhibited_fraction = 0.0;  // share of the image inhibited this frame, before selection
  // Milliseconds of the stage's parts: tracking, inhibition, selection.
  double track_ms = 0.0, inhibit_ms = 0.0, select_ms = 0.0;
};

// What AttentionStage::Track found in a frame, for Select in the same frame.
struct TrackedTargets {
  std::vector<TrackResult> results;  // one per target tracked, in id order
  cv::Mat skin;                      // the frame's binary skin map (CV_8UC1, 255 on skin)
  double milliseconds = 0.0;         // the time Track took
};

class AttentionStage {
 public:
  // `skin_model`: classifies pixels as skin for skin trackers and for choosing the similarity.
  // `pool`: the pool of its pyramids (the saliency segmentation's, the tracker's;
  // pyramid/bip.h), which must outlive the stage; nullptr: pools of their own.
  AttentionStage(const AttentionOptions& options, SkinModel skin_model, BipPool* pool = nullptr);
  ~AttentionStage();

  // The sequence's frame rate, which attention.dwell_s counts in (kDefaultFrameRate until set).
  void SetFrameRate(double fps);
  // The stereo pair's baseline in metres, for the heights of select.max_height (0: unknown).
  void SetBaseline(double baseline_m);
  static constexpr double kDefaultFrameRate = 25.0;

  // The model whose SkinDistanceMap the steps below take (FrameContext::SkinDistance).
  const SkinModel& skin_model() const;
  // Tracks the existing targets in the frame (8-bit BGR, with `skin_distance`, its
  // SkinDistanceMap for skin_model(), and optionally `cylinder`, its BgrToCylinder, which the
  // tracker then need not compute again) into `tracked`.
  void Track(const cv::Mat& bgr, const cv::Mat& skin_distance, TrackedTargets* tracked,
             const cv::Mat& cylinder = cv::Mat());
  // From the targets `tracked` in this frame: builds the inhibition, inhibits `saliency`,
  // selects and starts new targets on the colour regions of `segmentation`, and fills
  // `frame`. `detections`: the top-down channels' detections in this frame, which label the
  // targets and seed them with select.seed: detection. `stereo`: the frame's right view and
  // disparity, for each target's disparity and depth in the loop (the depth section).
  void Select(const cv::Mat& bgr, const cv::Mat& skin_distance, const TrackedTargets& tracked,
              const cv::Mat& saliency, const Segmentation& segmentation, AttentionFrame* frame,
              const std::vector<Detection>& detections = {}, const StereoInput& stereo = {});
  // Where attention looked in the last frame Select saw: the boxes of the targets it follows,
  // of its object files' predictions and of the candidates it weighed (at most
  // kLookCandidates, best first); FrameContext::AttentionRegions of the next frame.
  const std::vector<cv::Rect>& look_regions() const;
  static constexpr int kLookCandidates = 8;
  const ObjectFiles& object_files() const;

  const cv::Mat& inhibition() const;  // CV_32FC1, 0 or 1
  // The last frame's background (select.background): CV_8UC1, each pixel's BackgroundKind
  // (semiattentive/background.h), 0 off it; empty when off.
  const cv::Mat& background() const;
  const cv::Mat& inhibited() const;   // CV_32FC1
  int targets_attended() const;
  // The tracker kind that follows the targets ("bip", "kcf", "csrt").
  const char* tracker_name() const;

 private:
  // The targets, the object files, the tracker and the per-frame scratch.
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace attend
