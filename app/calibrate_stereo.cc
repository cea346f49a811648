#include "app/calibrate_stereo.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>
#include <regex>

#include "io/frame_files.h"
#include "stereo/row_check.h"
#include "util/error.h"

namespace attend {

namespace fs = std::filesystem;

namespace {

constexpr int kMinPairs = 3;

// One pair whose board was found in both views: its images and corners.
struct BoardPair {
  std::string left_path, right_path;
  cv::Mat left, right;  // 8-bit BGR, as read
  std::vector<cv::Point2f> left_corners, right_corners;
};

// The inner corners of `board` in `image`, refined to sub-pixel; empty when not found.
std::vector<cv::Point2f> FindCorners(const cv::Mat& image, cv::Size board) {
  cv::Mat grey;
  cv::cvtColor(image, grey, cv::COLOR_BGR2GRAY);
  std::vector<cv::Point2f> corners;
  const int flags = cv::CALIB_CB_ADAPTIVE_THRESH | cv::CALIB_CB_NORMALIZE_IMAGE;
  if (!cv::findChessboardCorners(grey, board, corners, flags)) return {};
  cv::cornerSubPix(grey, corners, cv::Size(11, 11), cv::Size(-1, -1),
                   cv::TermCriteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 30, 0.01));
  return corners;
}

std::string SizeText(cv::Size size) {
  return std::to_string(size.width) + "x" + std::to_string(size.height);
}

// The pairs of the two folders (sorted names) with the board found in both; the others go to
// `result->skipped`. Sets the image size.
std::vector<BoardPair> FindBoards(const CalibrateRequest& request, cv::Size* image_size,
                                  CalibrateResult* result) {
  const std::vector<std::string> left = ListFrameFiles(request.left, "--left " + request.left);
  const std::vector<std::string> right =
      ListFrameFiles(request.right, "--right " + request.right);
  if (left.empty() || right.empty()) {
    throw InputError("no pairs: " + (left.empty() ? request.left : request.right) +
                     " holds no images (.png, .jpg, .jpeg, .ppm, .pgm)");
  }
  if (left.size() != right.size()) {
    throw InputError("the folders do not pair: " + request.left + " has " +
                     std::to_string(left.size()) + " images, " + request.right + " has " +
                     std::to_string(right.size()));
  }
  result->pairs = static_cast<int>(left.size());
  std::vector<BoardPair> pairs;
  for (size_t i = 0; i < left.size(); ++i) {
    BoardPair pair{left[i], right[i], ReadFrameFile(static_cast<int>(i), left[i]),
                   ReadFrameFile(static_cast<int>(i), right[i]), {}, {}};
    if (image_size->area() == 0) *image_size = pair.left.size();
    if (pair.left.size() != *image_size || pair.right.size() != *image_size) {
      throw InputError("pair " + left[i] + ", " + right[i] + ": " + SizeText(pair.left.size()) +
                       " and " + SizeText(pair.right.size()) + ", but the first left view is " +
                       SizeText(*image_size) + "; every view must have the same size");
    }
    pair.left_corners = FindCorners(pair.left, request.board);
    pair.right_corners = FindCorners(pair.right, request.board);
    if (pair.left_corners.empty() || pair.right_corners.empty()) {
      const std::string where = pair.left_corners.empty() && pair.right_corners.empty()
                                    ? "either view"
                                    : (pair.left_corners.empty() ? "the left view"
                                                                 : "the right view");
      result->skipped.push_back({left[i], right[i],
                                 "no " + SizeText(request.board) + " board found in " + where});
      continue;
    }
    pairs.push_back(std::move(pair));
  }
  return pairs;
}

// The board's corners in metres, in its own plane.
std::vector<cv::Point3f> BoardPoints(cv::Size board, double square_m) {
  std::vector<cv::Point3f> points;
  for (int row = 0; row < board.height; ++row) {
    for (int column = 0; column < board.width; ++column) {
      points.emplace_back(static_cast<float>(column * square_m),
                          static_cast<float>(row * square_m), 0.0f);
    }
  }
  return points;
}

// The mean |y_left - y_right| of the boards' corners rectified through `c`.
double CornerRowError(const std::vector<BoardPair>& pairs, const StereoCalibration& c) {
  double sum = 0.0;
  size_t count = 0;
  for (const BoardPair& pair : pairs) {
    std::vector<cv::Point2f> left, right;
    cv::undistortPoints(pair.left_corners, left, c.K1, c.D1, c.R1, c.P1);
    cv::undistortPoints(pair.right_corners, right, c.K2, c.D2, c.R2, c.P2);
    for (size_t i = 0; i < left.size(); ++i) sum += std::abs(left[i].y - right[i].y);
    count += left.size();
  }
  return count > 0 ? sum / count : 0.0;
}

// The row check of every pair rectified through `c`.
void CheckRectifiedRows(const std::vector<BoardPair>& pairs, const StereoCalibration& c,
                        CalibrateResult* result) {
  const Rectifier rectifier(c);
  std::vector<double> offsets;
  for (const BoardPair& pair : pairs) {
    cv::Mat left = pair.left.clone(), right = pair.right.clone();
    rectifier.Apply(&left, &right);
    const RowCheck check = MeasureRowOffset(left, right);
    result->rectified_row_matches += check.matches;
    if (check.Decided()) offsets.push_back(check.row_offset_px);
  }
  result->rectified_row_pairs = static_cast<int>(offsets.size());
  if (offsets.empty()) return;
  std::sort(offsets.begin(), offsets.end());
  const size_t middle = offsets.size() / 2;
  result->rectified_row_offset_px = offsets.size() % 2 == 1
                                        ? offsets[middle]
                                        : 0.5 * (offsets[middle - 1] + offsets[middle]);
  result->rectified_row_offset_max_px = offsets.back();
}

void CheckRequest(const CalibrateRequest& request) {
  if (request.board.width < 2 || request.board.height < 2) {
    throw ConfigError("--board must be COLSxROWS inner corners, both >= 2 (9x6), got " +
                      SizeText(request.board));
  }
  if (!(request.square_m > 0) || !std::isfinite(request.square_m)) {
    throw ConfigError("--square must be the side of a square in metres, > 0, got " +
                      std::to_string(request.square_m));
  }
  if (!(request.alpha >= 0 && request.alpha <= 1)) {
    throw ConfigError("--alpha must be in [0, 1], got " + std::to_string(request.alpha));
  }
}

}  // namespace

cv::Size ParseBoardSize(const std::string& text) {
  static const std::regex pattern("([0-9]{1,4})[xX]([0-9]{1,4})");
  std::smatch match;
  if (!std::regex_match(text, match, pattern)) {
    throw ConfigError("--board must be COLSxROWS inner corners (9x6), got '" + text + "'");
  }
  const cv::Size board(std::stoi(match[1]), std::stoi(match[2]));
  if (board.width < 2 || board.height < 2) {
    throw ConfigError("--board must have at least 2 inner corners each way, got '" + text + "'");
  }
  return board;
}

CalibrateResult CalibrateStereo(const CalibrateRequest& request) {
  CheckRequest(request);
  CalibrateResult result;
  cv::Size size;
  const std::vector<BoardPair> pairs = FindBoards(request, &size, &result);
  result.pairs_used = static_cast<int>(pairs.size());
  if (result.pairs_used < kMinPairs) {
    std::string files;
    for (const SkippedPair& s : result.skipped) files += "; " + s.left + ", " + s.right + ": " + s.why;
    throw InputError("the board was found in both views of " + std::to_string(result.pairs_used) +
                     " pairs, fewer than the " + std::to_string(kMinPairs) +
                     " a calibration needs (is --board " + SizeText(request.board) +
                     " the inner corners?)" + files);
  }
  std::vector<std::vector<cv::Point3f>> objects(pairs.size(),
                                                BoardPoints(request.board, request.square_m));
  std::vector<std::vector<cv::Point2f>> left_corners, right_corners;
  for (const BoardPair& pair : pairs) {
    left_corners.push_back(pair.left_corners);
    right_corners.push_back(pair.right_corners);
  }
  // Each camera alone first: the intrinsics the stereo calibration starts from.
  StereoCalibration& c = result.calibration;
  c.form = StereoCalibration::Form::kFull;
  c.image_size = size;
  std::vector<cv::Mat> rvecs, tvecs;
  cv::Mat K1, D1, K2, D2;
  cv::calibrateCamera(objects, left_corners, size, K1, D1, rvecs, tvecs);
  cv::calibrateCamera(objects, right_corners, size, K2, D2, rvecs, tvecs);
  const cv::TermCriteria criteria(cv::TermCriteria::COUNT + cv::TermCriteria::EPS, 100, 1e-6);
  // Both ways; the lower RMS wins (docs/STEREO3D.md has the numbers).
  cv::Mat fixed_K1 = K1.clone(), fixed_D1 = D1.clone(), fixed_K2 = K2.clone(),
          fixed_D2 = D2.clone(), fixed_R, fixed_T, E, F;
  result.rms_fixed_px =
      cv::stereoCalibrate(objects, left_corners, right_corners, fixed_K1, fixed_D1, fixed_K2,
                          fixed_D2, size, fixed_R, fixed_T, E, F, cv::CALIB_FIX_INTRINSIC, criteria);
  c.K1 = K1.clone();
  c.D1 = D1.clone();
  c.K2 = K2.clone();
  c.D2 = D2.clone();
  result.rms_refined_px =
      cv::stereoCalibrate(objects, left_corners, right_corners, c.K1, c.D1, c.K2, c.D2, size,
                          c.R, c.T, E, F, cv::CALIB_USE_INTRINSIC_GUESS, criteria);
  result.method = "stereo, intrinsics refined";
  c.rms_px = result.rms_refined_px;
  if (result.rms_fixed_px < result.rms_refined_px) {
    result.method = "stereo, intrinsics fixed";
    c.K1 = fixed_K1, c.D1 = fixed_D1, c.K2 = fixed_K2, c.D2 = fixed_D2;
    c.R = fixed_R, c.T = fixed_T;
    c.rms_px = result.rms_fixed_px;
  }
  for (cv::Mat* m : {&c.K1, &c.D1, &c.K2, &c.D2, &c.R, &c.T}) m->convertTo(*m, CV_64F);
  cv::stereoRectify(c.K1, c.D1, c.K2, c.D2, size, c.R, c.T, c.R1, c.R2, c.P1, c.P2, c.Q,
                    cv::CALIB_ZERO_DISPARITY, request.alpha);
  if (std::abs(c.P2.at<double>(1, 3)) > std::abs(c.P2.at<double>(0, 3))) {
    throw InputError("the cameras are one above the other (stereoRectify made a vertical pair); "
                     "attend reads side-by-side pairs");
  }
  result.corner_row_error_px = CornerRowError(pairs, c);
  CheckRectifiedRows(pairs, c, &result);
  c.source = request.out;
  WriteStereoCalibration(c, request.out);
  // Read back: what was written is what a run reads.
  c = ReadStereoCalibration(request.out);
  return result;
}

nlohmann::ordered_json CalibrateResult::ToJson(const std::string& out) const {
  nlohmann::ordered_json skipped_json = nlohmann::ordered_json::array();
  for (const SkippedPair& s : skipped) {
    skipped_json.push_back({{"left", s.left}, {"right", s.right}, {"why", s.why}});
  }
  const StereoCalibration& c = calibration;
  return {{"out", out},
          {"rms_px", c.rms_px},
          {"method", method},
          {"rms_intrinsics_refined_px", rms_refined_px},
          {"rms_intrinsics_fixed_px", rms_fixed_px},
          {"pairs", pairs},
          {"pairs_used", pairs_used},
          {"skipped", skipped_json},
          {"image_size", {c.image_size.width, c.image_size.height}},
          {"focal_px", c.focal_px()},
          {"baseline_m", c.baseline_m()},
          {"rectified_row_offset_px", rectified_row_offset_px},
          {"rectified_row_offset_max_px", rectified_row_offset_max_px},
          {"rectified_row_pairs", rectified_row_pairs},
          {"rectified_row_matches", rectified_row_matches},
          {"corner_row_error_px", corner_row_error_px}};
}

}  // namespace attend
