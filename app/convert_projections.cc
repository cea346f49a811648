#include "app/convert_projections.h"

#include <cmath>
#include <string>
#include <vector>

#include "io/calibration_text.h"
#include "util/error.h"

namespace attend {

StereoCalibration ReadKittiProjections(const std::string& path, cv::Size size) {
  const CalibrationText file(path);
  const bool raw_set = file.Has("P_rect_02");
  const std::string left_key = raw_set ? "P_rect_02" : "P2";
  const std::string right_key = raw_set ? "P_rect_03" : "P3";
  if (size.area() == 0 && file.Has("S_rect_02")) {
    const std::vector<double> s = file.Numbers("S_rect_02", 2);
    size = cv::Size(static_cast<int>(std::lround(s[0])), static_cast<int>(std::lround(s[1])));
  }
  if (size.area() == 0) {
    throw InputError(path + ": has no S_rect_02 (the odometry set's calib.txt has none): give "
                     "the frames' size with --size WxH");
  }
  const cv::Mat left = file.Matrix(left_key, 3, 4);
  return RectifiedFromProjections(path, left, file.Matrix(right_key, 3, 4), size);
}

StereoCalibration ReadEurocProjections(const std::string& path) {
  const CalibrationText file(path);
  const double width = file.Numbers("width", 1)[0];
  const double height = file.Numbers("height", 1)[0];
  const cv::Size size(static_cast<int>(std::lround(width)), static_cast<int>(std::lround(height)));
  const cv::Mat left = file.Matrix("P_left", 3, 4);
  return RectifiedFromProjections(path, left, file.Matrix("P_right", 3, 4), size);
}

}  // namespace attend
