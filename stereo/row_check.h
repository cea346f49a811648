// The row check of a stereo pair (docs/STEREO3D.md, "The row check"): how far apart, in rows,
// the left and right views show the same points. A rectified pair shows every point on the
// same row of both views; a raw pair given as rectified (or a calibration gone wrong) does not,
// and every disparity measured along rows is then wrong. `attend run` checks its first stereo
// frame with it, `attend calibrate` the pairs it rectified.
#pragma once

#include <opencv2/core.hpp>

namespace attend {

// Above this median row offset (pixels of the native frames) a pair is not rectified: the real
// rectified pairs of the reference data measure 0.06-0.19 px at attend's working size, a right
// view moved 3 rows down 2.9-3.1 px, turned by 1 degree 1.0-2.6 px (docs/STEREO3D.md).
inline constexpr double kMaxRowOffsetPx = 0.75;
// Fewer matches than this give no verdict (a blank or repetitive view).
inline constexpr int kMinRowMatches = 20;

struct RowCheck {
  double row_offset_px = 0.0;  // median |y_left - y_right| over the matches, pixels of the views
  double row_shift_px = 0.0;   // median y_right - y_left (signed), pixels of the views
  int matches = 0;             // the matches the medians are over (the fit's inliers)

  // Whether the check can tell (enough matches).
  bool Decided() const { return matches >= kMinRowMatches; }
};

// Matches ORB features of `left` and `right` (8-bit, grey or BGR, the same size): mutual best
// matches that pass the ratio test, each refined to a tenth of a pixel by correlating its left
// patch around the match in the right view; kept when the right point is at or left of the
// left point (disparity >= 0) and inside the image, and when its row shift agrees, within a
// pixel, with the shift a + b x + c y that most matches agree with (RANSAC: repeated texture,
// a chessboard, matches features to the wrong repeat). An empty `right` gives no matches.
RowCheck MeasureRowOffset(const cv::Mat& left, const cv::Mat& right);

}  // namespace attend
