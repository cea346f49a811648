// The release rules of the attention stage (SPEC 2.4's drop rule and the size rules; see
// semiattentive/attention.h for the lifecycle). A found target is released, and inhibits
// nothing from that frame on, when the first of these holds (the reason recorded):
//   too_large     its mask covers more than select.max_area_fraction of the image
//   spans_image   its box spans the image: kSpansImageFraction of its width and its height
//   too_small     its box holds fewer than select.min_area pixels
//   low_saliency  its own uninhibited saliency stayed below drop.min_saliency for drop.frames
//                 frames in a row
//   duplicate     more than drop.max_shared of its mask is held by older targets found and kept
//                 this frame (HeldPixels)
// The "unrecognised" rule (drop.unrecognised_frames) is recognition's
// (semiattentive/recognition.h).
#pragma once

#include <opencv2/core.hpp>

#include "io/target_state.h"
#include "semiattentive/select_options.h"
#include "util/option_fields.h"

namespace attend {

// A found target whose box is at least this share of the image's width and of its height
// spans the image and is released ("spans_image").
constexpr double kSpansImageFraction = 0.9;

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

class ReleaseRules {
 public:
  ReleaseRules(const SelectOptions& select, const DropOptions& drop);

  // Whether the duplicate rule is on (drop.max_shared < 1).
  bool duplicates() const { return max_shared_ < 1.f; }
  // The frames in a row below drop.min_saliency, with this frame's `saliency` after
  // `low_frames` such frames.
  int LowFrames(double saliency, int low_frames) const;
  // Why a found target with this `box` and mask `area` is released this frame (kNone when it
  // is not), after `low_frames` frames of low saliency, `shared` of its mask held by older
  // targets, in an image of `image`.
  ReleaseReason WhyReleased(const cv::Rect& box, int area, int low_frames, double shared,
                            const cv::Rect& image) const;

 private:
  float max_area_fraction_;
  int min_area_;
  float min_saliency_;
  int frames_;
  float max_shared_;
};

// The pixels of the targets found and kept so far in a frame, in id order: a younger target
// most of whose mask an older one already holds is a duplicate (drop.max_shared).
class HeldPixels {
 public:
  // A new frame of `size`: nothing held.
  void Reset(cv::Size size);
  // The share of `mask` (CV_8UC1, of `area` pixels > 0) held already.
  double Shared(const cv::Mat& mask, int area) const;
  // Holds the pixels of `mask`.
  void Hold(const cv::Mat& mask) { held_.setTo(255, mask); }

 private:
  cv::Mat held_;  // CV_8UC1, 255 on the held pixels
};

}  // namespace attend
