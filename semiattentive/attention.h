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
#pragma once

#include <memory>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "colour/skin_model.h"
#include "features/skin.h"
#include "features/feature_map.h"
#include "pyramid/segmentation.h"
#include "semiattentive/object_files.h"
#include "io/target_state.h"
#include "tracker/target_tracker.h"

namespace attend {

// A found target whose box is at least this share of the image's width and of its height
// spans the image and is released ("spans_image").
constexpr double kSpansImageFraction = 0.9;

// What a candidate starts as (SelectOptions::seed).
enum class SeedKind { kRegion, kObject, kDetection };
// "region", "object", "detection" (the select.seed key).
const char* SeedKindName(SeedKind seed);

struct SelectOptions {
  float min_saliency = 0.2f;  // mean inhibited saliency of a candidate region, 0..1
  int min_area = 120;         // pixels, at the working size
  int max_new = 2;            // targets started in one frame
  int max_targets = 12;       // targets active at once
  // A colour region larger than this share of the image is background, never a target.
  float max_area_fraction = 0.2f;
  // No new target starts while the inhibition (with the new region) would cover more than
  // this share of the image; 1: no bound (the thesis's).
  float max_inhibited_fraction = 0.3f;
  // T_max of the BIP that segments the saliency map, in saliency units times 255.
  float saliency_t_max = 40.f;
  // What a candidate starts as: "region", the colour region it overlaps most (thesis 5.1.2),
  // or "object", that region together with every colour region of which at least
  // `seed_share` lies inside the candidate's salient region (an object of several colours,
  // such as a person's coat, trousers and head). The object's area is bounded as a region's.
  // "detection": where the candidate's most salient pixel lies in a top-down channel's
  // detection box (features/detectors.h), the colour regions of which at least `seed_share`
  // lies inside that box (a whole person), and a candidate inside a detection that an active
  // target already covers by `detection_taken` of its box is part of that target, not a new
  // one; elsewhere as "object".
  SeedKind seed = SeedKind::kRegion;
  float detection_taken = 0.3f;
  // "detection" only: a candidate under no detection starts nothing (the channels are told
  // where it is, through the look regions, and recognise it in the next frames), so that
  // every target is a recognised object; false: it starts as an "object" seed.
  bool detected_only = false;
  // Recognition keeps a target on its object: a found target whose box and a detection's
  // overlap with IoU in [reanchor_min_iou, reanchor_max_iou) starts again from that
  // detection's colour regions, under its own id (its tracker had slid off part of the
  // object). 0: never.
  float reanchor_min_iou = 0.f;
  float reanchor_max_iou = 0.75f;
  // ... and only when what the detection's seed looks like (ObjectAppearance::Similarity)
  // is at least this like what the target looked like on its object: a target that slid
  // onto the person beside it is not restarted on them (it is left as it is, unrecognised).
  // 0: any look.
  float reanchor_min_similarity = 0.f;
  float seed_share = 0.5f;
  // object: the candidate's salient region is the connected area around its most salient
  // pixel where the inhibited saliency is at least this times the candidate's mean.
  float seed_level = 0.5f;
  // object: motion grouping. Where the proto-object moves at least this fast (px a frame, its
  // regions' mean dense optical flow from the previous frame, OpenCV's DIS), the colour
  // regions next to it that move alike join it, region by region outwards: a region whose mean
  // flow differs from the proto-object's by at most group_flow_tolerance times its speed.
  // 0: off (the thesis's stage has no motion).
  float group_min_speed = 0.f;
  float group_flow_tolerance = 0.5f;
  // The fields (util/option_fields.h), for AttentionOptions::Check and the configuration's
  // `select` section.
  static const OptionFields<SelectOptions>& Fields();
};

struct DropOptions {
  float min_saliency = 0.1f;  // a target below this, uninhibited, for `frames` is released
  int frames = 15;
  // A found target more than this share of whose mask older found targets (kept this frame)
  // already hold is a duplicate and is released ("duplicate"): a tracker that slid onto
  // another target's object. 1: never (the thesis's stage).
  float max_shared = 0.5f;
  // A labelled target that no detection has overlapped (IoU >= select.reanchor_min_iou, or
  // 0.3 when that is 0) for this many frames in a row while the channels reported detections
  // is released ("unrecognised"): its tracker has left the object. 0: never.
  int unrecognised_frames = 0;
  static const OptionFields<DropOptions>& Fields();
};

struct InhibitionOptions {
  int margin = 3;             // pixels of dilation around each tracked mask
  bool keep_occluded = true;  // occluded targets inhibit their last box
  // ... and the area their tracker searched them in this frame (the box and its ROI border):
  // an object that reappears there is the occluded target coming back, not a new one.
  bool occluded_search = true;
  static const OptionFields<InhibitionOptions>& Fields();
};

struct AttentionOptions {
  SelectOptions select;
  DropOptions drop;
  InhibitionOptions inhibition;
  TargetTrackerOptions tracker;  // the kind and its options (tracker/target_tracker.h)
  // A target is a skin target when at least this share of its colour region is skin, by the
  // skin model in `skin_model` (a file as made by attend skin-train).
  float skin_fraction = 0.5f;
  std::string skin_model = "configs/skin_tsl.yaml";
  // Whether a mostly-skin region must also be confident, skin-shaped skin to start a skin
  // target (false: the thesis's rule, the share alone), and the bounds of that test.
  bool skin_check = true;
  SkinRegionOptions skin_region;
  // Object files: the memory of objects that ended (semiattentive/object_files.h); off when
  // memory.memory_frames is 0.
  ObjectFileOptions memory;
  // A target takes the label of a top-down detection ("person", "face") whose box and its own
  // overlap by at least this share of the larger of the two.
  float label_overlap = 0.5f;
  // "" when valid; otherwise names the field and the broken constraint.
  std::string Check() const;
  // This struct's own fields (the `select` keys label_overlap, skin_*).
  static const OptionFields<AttentionOptions>& Fields();
};

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
  // targets and seed them with select.seed: detection.
  void Select(const cv::Mat& bgr, const cv::Mat& skin_distance, const TrackedTargets& tracked,
              const cv::Mat& saliency, const Segmentation& segmentation, AttentionFrame* frame,
              const std::vector<Detection>& detections = {});
  // Where attention looked in the last frame Select saw: the boxes of the targets it follows,
  // of its object files' predictions and of the candidates it weighed (at most
  // kLookCandidates, best first); FrameContext::AttentionRegions of the next frame.
  const std::vector<cv::Rect>& look_regions() const;
  static constexpr int kLookCandidates = 8;
  const ObjectFiles& object_files() const;

  const cv::Mat& inhibition() const;  // CV_32FC1, 0 or 1
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
