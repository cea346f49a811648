// The scores of a disparity map against ground truth (SPEC 4): Middlebury's bad-pixel rates.
#pragma once

#include <opencv2/core.hpp>

namespace attend {

// Bad-pixel rates of SPEC 4 (Middlebury): the share of pixels with known ground truth
// (`ground_truth` > 0 and finite, CV_32FC1 in pixels) where |d - d_gt| > 1 and > 2; invalid
// estimates (negative or not finite) count as bad.
struct BadPixelRates {
  double bad1 = 0.0;
  double bad2 = 0.0;
  int known = 0;
};
BadPixelRates EvaluateDisparity(const cv::Mat& disparity, const cv::Mat& ground_truth);

}  // namespace attend
