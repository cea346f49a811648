// Saliency baselines scored beside attend's maps (docs/FIXATIONS.md): a centre bias,
// and OpenCV's spectral residual (Hou & Zhang, CVPR 2007) and fine-grained (Montabone & Soto,
// 2010) static saliency from the contrib module `saliency`.
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace attend {

// "centre", "spectral_residual", "fine_grained".
const std::vector<std::string>& BaselineNames();

// The baseline `name`'s map of `bgr` (8-bit BGR), CV_32FC1 at bgr's size, min-max normalised to
// [0, 1], then blurred by a Gaussian of `blur` x the larger side (0: none). The centre bias is
// the Gaussian of CentreBias (eval/fixation_metrics.h) and is not blurred. Throws
// std::invalid_argument for an unknown name.
cv::Mat BaselineMap(const std::string& name, const cv::Mat& bgr, double blur);

}  // namespace attend
