#include "tracker/bounded_refinement.h"

#include <algorithm>
#include <cmath>

#include "tracker/refinement.h"

namespace attend {
namespace tracker_internal {

cv::Rect BoundedRefinement::BoundTarget(const Hierarchy& h, const Target& target, cv::Point shift,
                                        const cv::Rect& image, std::vector<uint8_t>* in_target) {
  const cv::Rect moved = target.box + shift;
  const int gx = std::max(2, static_cast<int>(std::lround(options_.bound_growth * moved.width)));
  const int gy = std::max(2, static_cast<int>(std::lround(options_.bound_growth * moved.height)));
  const cv::Rect plausible =
      cv::Rect(moved.x - gx, moved.y - gy, moved.width + 2 * gx, moved.height + 2 * gy) &
      target.roi & image;
  const std::vector<uint8_t> matched = *in_target;
  Refine(h, plausible, options_.t_refine, in_target);
  inside_.assign(h.regions, 0);
  all_.assign(h.regions, 0);
  const BipLevel& base = h.bip->level(0);
  const cv::Rect roi = target.roi & cv::Rect(h.origin, h.size);
  for (int y = roi.y; y < roi.y + roi.height; ++y) {
    const int row = (y - h.origin.y) * base.cols - h.origin.x;
    const bool y_in = y >= moved.y && y < moved.y + moved.height;
    for (int x = roi.x; x < roi.x + roi.width; ++x) {
      const int cell = row + x;
      if (!base.hom[cell]) continue;
      const int r = h.region[0][cell];
      if (r < 0 || !(*in_target)[r]) continue;
      ++all_[r];
      if (y_in && x >= moved.x && x < moved.x + moved.width) ++inside_[r];
    }
  }
  bool any = false;
  for (int r = 0; r < h.regions; ++r) {
    if (!(*in_target)[r]) continue;
    (*in_target)[r] = 2 * inside_[r] >= all_[r];
    any = any || (*in_target)[r];
  }
  // When every region reaches out, the matched regions are kept, cut to the box.
  if (!any) *in_target = matched;
  return plausible;
}

cv::Rect BoundedRefinement::SmoothBox(const Target& target, cv::Point shift, cv::Rect mask_box,
                                      const cv::Rect& plausible, const cv::Rect& image,
                                      cv::Rect2d* smooth) const {
  const cv::Rect moved = target.box + shift;
  // The unrounded box moved as the rounded one: only its size and sub-pixel offset carry.
  const cv::Rect2d last = target.smooth.area() > 0 ? target.smooth : cv::Rect2d(target.box);
  const cv::Rect2d moved_smooth(last.x + shift.x, last.y + shift.y, last.width, last.height);
  int x0 = mask_box.x, y0 = mask_box.y;
  int x1 = mask_box.x + mask_box.width, y1 = mask_box.y + mask_box.height;
  if (x0 <= plausible.x && plausible.x > 0) x0 = std::max(x0, moved.x);
  if (y0 <= plausible.y && plausible.y > 0) y0 = std::max(y0, moved.y);
  if (x1 >= plausible.x + plausible.width && x1 < image.width) {
    x1 = std::min(x1, moved.x + moved.width);
  }
  if (y1 >= plausible.y + plausible.height && y1 < image.height) {
    y1 = std::min(y1, moved.y + moved.height);
  }
  if (x1 <= x0 || y1 <= y0) return moved & image;
  const double rate = options_.size_rate;
  const double w = (1 - rate) * moved_smooth.width + rate * (x1 - x0);
  const double hgt = (1 - rate) * moved_smooth.height + rate * (y1 - y0);
  const double crate = options_.centre_rate;
  const double cx =
      (1 - crate) * (moved_smooth.x + moved_smooth.width / 2.0) + crate * (x0 + x1) / 2.0;
  const double cy =
      (1 - crate) * (moved_smooth.y + moved_smooth.height / 2.0) + crate * (y0 + y1) / 2.0;
  *smooth = cv::Rect2d(cx - w / 2, cy - hgt / 2, std::max(1.0, w), std::max(1.0, hgt));
  cv::Rect box(static_cast<int>(std::lround(cx - w / 2)),
               static_cast<int>(std::lround(cy - hgt / 2)),
               std::max(1, static_cast<int>(std::lround(w))),
               std::max(1, static_cast<int>(std::lround(hgt))));
  box &= image;
  return box.empty() ? (moved & image) : box;
}

}  // namespace tracker_internal
}  // namespace attend
