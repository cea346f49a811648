// The files of `attend disparity`: a stereo image, a ground-truth disparity map and the
// disparity map it writes (docs/DISPARITY.md).
#pragma once

#include <opencv2/core.hpp>
#include <string>

namespace attend {

// An image of a stereo pair as the estimator takes it: 8-bit, grey files stay grey, colour
// files become BGR (alpha dropped), 16-bit samples are scaled to 8 bits. InputError naming the
// file when it is missing or cannot be decoded.
cv::Mat ReadStereoImage(const std::string& path);

// Ground truth in pixels (CV_32FC1): a one-channel PFM, or a one-channel 8- or 16-bit image,
// each value divided by `scale`. Zero (and, in a PFM, infinity) stays unknown. InputError
// naming the file otherwise.
cv::Mat ReadDisparityGroundTruth(const std::string& path, double scale);

// Writes `disparity` as PFM beside `path` and renames it into place, so that `path` is either
// the complete new map or untouched; creates the folder. OutputError naming the file.
void WriteDisparityMap(const std::string& path, const cv::Mat& disparity);

}  // namespace attend
