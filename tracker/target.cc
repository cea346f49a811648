#include "tracker/target.h"

#include <algorithm>
#include <opencv2/imgproc.hpp>

#include "tracker/refinement.h"

namespace attend {
namespace tracker_internal {

int TakeFound(const Hierarchy& h, const std::vector<uint8_t>& in_target, const cv::Rect& keep,
              cv::Point shift, int pyramid_levels, const TrackerOptions& options,
              cv::Size frame_size, Target* target) {
  PaintTarget(h, in_target, keep, frame_size, &target->mask);
  target->levels =
      MakeTemplate(h, in_target, keep, &target->levels, shift, pyramid_levels, options.alpha);
  // The target's pixels all lie in its ROI.
  const cv::Moments moments = cv::moments(target->mask(target->roi), true);
  if (moments.m00 > 0) {
    target->centroid = {static_cast<float>(target->roi.x + moments.m10 / moments.m00),
                        static_cast<float>(target->roi.y + moments.m01 / moments.m00)};
  }
  target->motion = shift;
  target->border = options.EpsilonPixels(frame_size.width);
  return static_cast<int>(moments.m00);
}

void TakeMissed(float alpha, int epsilon_max, Target* target) {
  target->mask.release();
  Decay(alpha, &target->levels);
  target->border = std::min(target->border + 1, epsilon_max);
  target->motion = {0, 0};
}

}  // namespace tracker_internal
}  // namespace attend
