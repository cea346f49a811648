// The tracker's modes (TrackerOptions::mode) as policies, a class each, chosen once when a
// MultiTracker is made: ThesisMode (thesis_mode.cc), chapter 4 as written, and BoundedMode
// (bounded_mode.cc), the variant for real footage (docs/TRACKING.md, "Modes"). The
// MultiTracker (tracker.cc) keeps the targets and builds the pyramid over their regions of
// interest; a mode decides how a target starts and how it is searched for, found and missed.
// Not part of the API.
#pragma once

#include <memory>
#include <opencv2/core.hpp>

#include "tracker/roi_pyramid.h"
#include "tracker/target.h"
#include "tracker/tracker_options.h"

namespace attend {
namespace tracker_internal {

class ModePolicy {
 public:
  virtual ~ModePolicy() = default;

  // The frame (8-bit BGR) and its cylinder image (may be empty) as this mode's steps read it.
  virtual TrackFrame Frame(const cv::Mat& bgr, const cv::Mat& cylinder) = 0;

  // Whether a colour target started from a box is the whole box (else the regions that the
  // colour segmentation finds mostly inside it, thesis 4.2.1).
  virtual bool BoxIsTarget() const = 0;
  // Where a target started from `mask` may lie: its pixels and template are cut to this box.
  virtual cv::Rect StartBounds(const cv::Mat& mask, cv::Size frame_size) const = 0;
  // What a new target learns from its first frame (8-bit BGR) besides its template; `h` is
  // the over-segmentation of `built`, the mask's box and its border.
  virtual void Start(const cv::Mat& frame, const Hierarchy& h, const cv::Rect& built,
                     Target* target) = 0;

  // The target in a frame: searched in `h`, its part of the pyramid over the ROIs (nullptr
  // when its ROI is empty), whose tallest part has `pyramid_levels` levels. Found, it takes
  // its new pixels, box and template; not found, it decays. Sets the result's state, level,
  // area and overlap.
  virtual void Track(const TrackFrame& frame, const Hierarchy* h, int pyramid_levels,
                     Target* target, TrackResult* result) = 0;
};

std::unique_ptr<ModePolicy> MakeThesisMode(const TrackerOptions& options);
std::unique_ptr<ModePolicy> MakeBoundedMode(const TrackerOptions& options);

}  // namespace tracker_internal
}  // namespace attend
