// Depth contrast: how much nearer a pixel is than what surrounds it, figure against ground
// (the default score of the `disparity` feature; its `score: nearness` is the thesis's).
//
// Nearness alone ranks the road just in front of a car's camera first in every street scene,
// and a wall near a robot above the objects before it. What stands out to a viewer is an
// object nearer than its surround. For a pixel of measured disparity d at row v:
//   surround  = max(ground's disparity at v (when a ground plane was found), the least measured
//               disparity of at least half a pixel within a square of side `window` around it:
//               the farthest surface near it, the object's background; a sky the matcher put at
//               infinity is no surround, or everything before it would score 1)
//   contrast  = max(0, d - surround - 1) / d, in [0, 1]: about 1 - Z / Z_surround, the share by
//               which it
//               is nearer, whatever its distance (a car at 30 m before a facade at 60 m scores
//               as one at 5 m before a wall at 10 m); the pixel taken off is the matcher's noise,
//               which the least of many values in the window is below the rest by.
// The ground scores 0 (it is its own surround), and so does a pixel without a measured
// disparity: the sky and blank walls carry no depth evidence.
#pragma once

#include <opencv2/core.hpp>

#include "stereo/ground_plane.h"

namespace attend {

// `disparity` CV_32FC1 and `measured` CV_8UC1 (255 where measured) of one size; `window` odd,
// >= 3. Returns CV_32FC1 in [0, 1].
cv::Mat DepthContrast(const cv::Mat& disparity, const cv::Mat& measured, const GroundPlane& ground,
                      int window);

}  // namespace attend
