// Per-region disparity against ground truth (`attend disparity --gt GT --regions F`; issue 44):
// the left image is segmented by the BIP (the segmentation section's defaults), and each region
// larger than F of the image stands for a target whose mask it is. Each is given its disparity
// both ways of semiattentive/target_depth.h (the thesis's template in the right image; the
// interquartile mean of the dense map over it), and each is compared with the ground truth's
// median over the region's known pixels.
#pragma once

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>

#include "semiattentive/target_depth.h"
#include "stereo/disparity.h"

namespace attend {

// `left`, `right`: 8-bit, grey or BGR; `disparity`: the dense map (CV_32FC1) of `options`;
// `truth`: CV_32FC1, 0 unknown. Regions without a known ground-truth pixel are counted and
// left out. Returns {"min_fraction", "regions", "skipped", per method "within_1px",
// "median_abs_error_px", "mean_abs_error_px", and "per_region": [...]}.
nlohmann::json ScoreRegionDisparities(const cv::Mat& left, const cv::Mat& right,
                                      const cv::Mat& disparity, const cv::Mat& truth,
                                      const DisparityOptions& options, double min_fraction);

}  // namespace attend
