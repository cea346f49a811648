// The controller of `attend calibrate` (docs/STEREO3D.md, "Calibration"): a stereo camera's
// calibration from chessboard pairs (cv::findChessboardCorners, cv::calibrateCamera,
// cv::stereoCalibrate, cv::stereoRectify), written as calib.yaml (io/stereo_calibration.h),
// with the row check of its pairs rectified through it. The conversions of rectified
// projections are in app/convert_projections.h. The command only parses its arguments and
// prints.
#pragma once

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "io/stereo_calibration.h"

namespace attend {

struct CalibrateRequest {
  std::string left;   // LDIR: the left views, paired with RDIR's by sorted name
  std::string right;  // RDIR
  cv::Size board;     // the chessboard's inner corners, columns x rows (9x6 for 10x7 squares)
  double square_m = 0.0;  // the side of a square, metres (> 0)
  // cv::stereoRectify's free scaling: 0 keeps only pixels valid in both rectified views (no
  // black border, some of the field of view lost), 1 keeps every source pixel (black borders).
  double alpha = 0.0;
  std::string out;  // calib.yaml
};

// A pair that took no part, and why.
struct SkippedPair {
  std::string left, right, why;
};

struct CalibrateResult {
  StereoCalibration calibration;  // kFull, rms_px set
  // How the RMS was reached: "stereo, intrinsics refined" (stereoCalibrate with
  // CALIB_USE_INTRINSIC_GUESS from calibrateCamera's) or "stereo, intrinsics fixed"
  // (CALIB_FIX_INTRINSIC); both are run and the lower RMS is kept.
  std::string method;
  double rms_refined_px = 0.0;  // both RMS errors, for the record
  double rms_fixed_px = 0.0;
  int pairs = 0;       // pairs found in the folders
  int pairs_used = 0;  // with the board found in both views
  std::vector<SkippedPair> skipped;
  // The pairs rectified through the calibration: median over the pairs the row check decides
  // on (stereo/row_check.h: enough matches) of its median row offset, its largest, how many
  // pairs it decided on, and the features matched in all pairs.
  double rectified_row_offset_px = 0.0;
  double rectified_row_offset_max_px = 0.0;
  int rectified_row_pairs = 0;
  int rectified_row_matches = 0;
  // The board's corners rectified (cv::undistortPoints through R1, P1 and R2, P2): the mean
  // |y_left - y_right|, the classic epipolar error.
  double corner_row_error_px = 0.0;

  // The JSON object `attend calibrate` prints.
  nlohmann::ordered_json ToJson(const std::string& out) const;
};

// Calibrates from the pairs of `request` and writes request.out. ConfigError for a bad board
// or square size; InputError naming the files for no pairs, folders of different counts,
// views of different sizes, or fewer than 3 pairs with the board in both views; OutputError
// when request.out cannot be written.
CalibrateResult CalibrateStereo(const CalibrateRequest& request);

// "9x6" -> 9 columns, 6 rows of inner corners; ConfigError unless both are >= 2.
cv::Size ParseBoardSize(const std::string& text);

}  // namespace attend
