#include "app/convert_projections.h"

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "util/error.h"

namespace attend {

namespace {

// The "key: numbers" lines of a calibration text file (KITTI, EuRoC); '#' starts a comment.
class ProjectionFile {
 public:
  explicit ProjectionFile(const std::string& path) : path_(path) {
    std::ifstream in(path);
    if (!in) throw InputError(path + ": cannot read the calibration file");
    std::string line;
    while (std::getline(in, line)) {
      const size_t hash = line.find('#');
      if (hash != std::string::npos) line.resize(hash);
      const size_t colon = line.find(':');
      if (colon == std::string::npos) continue;
      std::string key = line.substr(0, colon);
      while (!key.empty() && std::isspace(static_cast<unsigned char>(key.back()))) key.pop_back();
      std::istringstream values(line.substr(colon + 1));
      std::vector<double> numbers;
      double value = 0.0;
      while (values >> value) numbers.push_back(value);
      // A key whose value is not all numbers (KITTI's calib_time) keeps what it read.
      entries_[key] = numbers;
    }
  }

  bool Has(const std::string& key) const { return entries_.count(key) > 0; }

  std::vector<double> Numbers(const std::string& key, size_t count) const {
    const auto it = entries_.find(key);
    if (it == entries_.end()) throw InputError(path_ + ": " + key + " is missing");
    if (it->second.size() != count) {
      throw InputError(path_ + ": " + key + " must hold " + std::to_string(count) +
                       " numbers, got " + std::to_string(it->second.size()));
    }
    for (double v : it->second) {
      if (!std::isfinite(v)) throw InputError(path_ + ": " + key + " has a value that is not finite");
    }
    return it->second;
  }

  cv::Mat Projection(const std::string& key) const {
    const std::vector<double> numbers = Numbers(key, 12);
    return cv::Mat(3, 4, CV_64F, const_cast<double*>(numbers.data())).clone();
  }

  const std::string& path() const { return path_; }

 private:
  std::string path_;
  std::map<std::string, std::vector<double>> entries_;
};

// The rectified form of projections `left` and `right` that share their intrinsics, both in
// a common rectified frame (KITTI's is camera 0's): P1 = [K | 0], P2 = [K | right - left] in
// the left camera's frame. Checked as ReadStereoCalibration checks a file.
StereoCalibration Rectified(const ProjectionFile& file, const cv::Mat& left, const cv::Mat& right,
                            cv::Size size) {
  if (size.width < 1 || size.height < 1) {
    throw InputError(file.path() + ": the image size is not known (give --size WxH)");
  }
  StereoCalibration c;
  c.form = StereoCalibration::Form::kRectified;
  c.source = file.path();
  c.image_size = size;
  c.P1 = left.clone();
  c.P1.col(3).setTo(0.0);
  c.P2 = right.clone();
  c.P2.col(3) = right.col(3) - left.col(3);
  if (c.P1.at<double>(0, 0) <= 0 || c.P2.at<double>(0, 0) <= 0) {
    throw InputError(file.path() + ": the focal length is not positive");
  }
  if (!(c.baseline_m() > 0)) {
    throw InputError(file.path() + ": the right camera is not to the right of the left one "
                     "(baseline " + std::to_string(c.baseline_m()) + " m)");
  }
  // Q and the identity rectifications as the reader makes them.
  StereoCalibration nominal = NominalCalibration(c.focal_px(), c.baseline_m(), size, c.source);
  c.R1 = nominal.R1;
  c.R2 = nominal.R2;
  c.Q = nominal.Q;
  c.Q.at<double>(0, 3) = -c.cx();
  c.Q.at<double>(1, 3) = -c.cy();
  c.Q.at<double>(3, 3) = (c.cx() - c.P2.at<double>(0, 2)) / (-c.baseline_m());
  return c;
}

}  // namespace

StereoCalibration ReadKittiProjections(const std::string& path, cv::Size size) {
  const ProjectionFile file(path);
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
  const cv::Mat left = file.Projection(left_key);
  return Rectified(file, left, file.Projection(right_key), size);
}

StereoCalibration ReadEurocProjections(const std::string& path) {
  const ProjectionFile file(path);
  const double width = file.Numbers("width", 1)[0];
  const double height = file.Numbers("height", 1)[0];
  const cv::Size size(static_cast<int>(std::lround(width)), static_cast<int>(std::lround(height)));
  const cv::Mat left = file.Projection("P_left");
  return Rectified(file, left, file.Projection("P_right"), size);
}

}  // namespace attend
