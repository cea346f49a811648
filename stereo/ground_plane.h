// The ground plane of a stereo frame, from its disparity map (the "v-disparity" of Labayrade,
// Aubert and Tarel, IV 2002). Seen by a rectified pair whose rows are level with the ground, a
// flat ground's disparity depends on the image row alone and grows linearly below the horizon:
//   d(v) = slope * (v - horizon_v),   slope = baseline / camera height,
// so the row-wise histogram of the measured disparities holds the ground as a line of positive
// slope, while an upright surface facing the camera (a wall, a car's back, a person) holds one
// disparity over many rows: a vertical line. The fit:
//   1. for every row, the disparity bin that most measured pixels of that row fall in, with its
//      count as the row's weight (rows where fewer than kMinRowShare of the width were measured
//      are left out);
//   2. RANSAC over pairs of those rows: the line of positive slope whose inliers (rows whose
//      mode lies within kModeTolerance of it) weigh most, among those that explain at least half
//      the weight of the lowest fifth of the rows (the ground is what the camera stands on: a
//      wall leaning back also grows in disparity downwards, but ends where the floor begins);
//      then least squares over its inliers;
//   3. the fit is a ground only when its inlier rows span at least kMinSpan of the image's
//      height and hold at least kMinSupport of its pixels, and its horizon lies above the
//      image's lower edge.
// The random pairs come from a fixed seed: the same frame gives the same plane.
#pragma once

#include <opencv2/core.hpp>

namespace attend {

struct GroundPlane {
  bool valid = false;
  double slope = 0.0;      // disparity pixels per image row
  double horizon_v = 0.0;  // the row where the ground's disparity reaches 0
  int support = 0;         // measured pixels on the fitted line's rows, at their mode

  // The ground's disparity at row v (0 at and above the horizon).
  double DisparityAt(double v) const { return v > horizon_v ? slope * (v - horizon_v) : 0.0; }
  // Whether disparity d at row v lies on the ground: below the horizon, within
  // kPixelTolerance + kRelativeTolerance * d of the ground's disparity there.
  bool OnGround(double v, double d) const;

  static constexpr double kPixelTolerance = 1.0;
  static constexpr double kRelativeTolerance = 0.1;
};

// The ground plane of `disparity` (CV_32FC1, pixels) over the pixels `measured` marks (CV_8UC1,
// 255 where the disparity was measured: DisparityEstimator::measured). Not valid when the
// frame shows no ground (a wall, a table top seen from above, too little measured).
GroundPlane FitGroundPlane(const cv::Mat& disparity, const cv::Mat& measured);

// The pixels of `disparity` that `measured` marks and that lie on `ground` (CV_8UC1, 255 on
// them); all 0 when the ground is not valid.
cv::Mat GroundMask(const cv::Mat& disparity, const cv::Mat& measured, const GroundPlane& ground);

}  // namespace attend
