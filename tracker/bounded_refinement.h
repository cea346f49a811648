// The bounded mode's refinement and box (docs/TRACKING.md, "Modes" 1-3): the target may only
// be where its last box, moved by the match, plausibly is now, and its box follows the
// evidence of its pixels by a share a frame. Not part of the API.
#pragma once

#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

#include "tracker/roi_pyramid.h"
#include "tracker/target.h"
#include "tracker/tracker_options.h"

namespace attend {
namespace tracker_internal {

class BoundedRefinement {
 public:
  explicit BoundedRefinement(const TrackerOptions& options) : options_(options) {}

  // The plausible box: the target's box moved by `shift` pixels, grown by `bound_growth` of
  // its size on each side (in its ROI and the image). Refinement (4.2.4) looks only there, and
  // a region (matched or refined) stays the target's only when most of its pixels in the ROI
  // lie in the moved box: a region that reaches far outside it is background that the
  // over-segmentation joined to the target. Returns the plausible box.
  cv::Rect BoundTarget(const Hierarchy& h, const Target& target, cv::Point shift,
                       const cv::Rect& image, std::vector<uint8_t>* in_target);

  // The box. The mask's box says where the target is, but a side of it that reaches the
  // plausible box's edge is no evidence of growth (the regions may go on beyond it): that side
  // stays where the moved box has it. The box's size and centre then follow that evidence by
  // `size_rate` and `centre_rate` a frame, so that one frame whose segmentation takes too
  // little or too much does not make the box jump. `*smooth`: the box before rounding.
  cv::Rect SmoothBox(const Target& target, cv::Point shift, cv::Rect mask_box,
                     const cv::Rect& plausible, const cv::Rect& image, cv::Rect2d* smooth) const;

 private:
  TrackerOptions options_;
  std::vector<int> inside_, all_;  // BoundTarget's counts per region, reused
};

}  // namespace tracker_internal
}  // namespace attend
