// Stereo pairs whose geometry is known by construction, for the calibration and row check
// tests: a textured plane parallel to the rectified views, seen by two cameras of a known
// full calibration (io/stereo_calibration.h).
#pragma once

#include <cstdint>
#include <opencv2/core.hpp>

#include "io/stereo_calibration.h"

namespace attend::testing {

// 8-bit BGR texture: smoothed noise with blocks of colour, rich in corners, seeded.
cv::Mat TexturedImage(cv::Size size, std::uint64_t seed);

struct KnownPair {
  StereoCalibration calibration;  // kFull: K1 = K2, no distortion, R, T, and stereoRectify's
                                  // R1, R2, P1, P2, Q (alpha 0), at `size`
  cv::Mat rectified_left, rectified_right;  // the plane as the rectified cameras see it
  cv::Mat raw_left, raw_right;              // and as the raw cameras do
};

// The rectified right view is the left one moved `disparity` pixels left along its rows (a
// fronto-parallel plane); the raw views are the rectified ones through the inverse of each
// camera's rectifying homography. The right camera is turned by about 2 degrees, so the raw
// views' rows differ by several pixels.
KnownPair MakeKnownPair(cv::Size size, double disparity, std::uint64_t seed = 7);

// `image` moved down by `rows` pixels (rows above filled from the edge).
cv::Mat ShiftDown(const cv::Mat& image, double rows);
// `image` turned by `degrees` about its centre.
cv::Mat Rotate(const cv::Mat& image, double degrees);

}  // namespace attend::testing
