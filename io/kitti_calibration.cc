#include "io/kitti_calibration.h"

#include <cmath>
#include <filesystem>
#include <vector>

#include "io/calibration_text.h"
#include "util/error.h"

namespace attend {

namespace fs = std::filesystem;

namespace {

cv::Matx34d Matx34(const cv::Mat& m) {
  cv::Matx34d out;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 4; ++c) out(r, c) = m.at<double>(r, c);
  }
  return out;
}

// A rotation (3x3) and a translation (3x1) as one 4x4 transform.
cv::Matx44d Transform(const cv::Mat& rotation, const cv::Mat& translation) {
  cv::Matx44d out = cv::Matx44d::eye();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) out(r, c) = rotation.at<double>(r, c);
    out(r, 3) = translation.at<double>(r, 0);
  }
  return out;
}

// The rig of the two projections; the Velodyne's pose is set by the caller.
KittiRig MakeRig(const std::string& source, const cv::Mat& left, const cv::Mat& right,
                 cv::Size size) {
  KittiRig rig;
  rig.stereo = RectifiedFromProjections(source, left, right, size);
  rig.left_projection = Matx34(left);
  return rig;
}

}  // namespace

cv::Matx33d KittiRig::K() const { return left_projection.get_minor<3, 3>(0, 0); }

cv::Vec3d KittiRig::LeftCameraFromRect(const cv::Vec3d& x_rect) const {
  const cv::Vec3d shift =
      K().inv() * cv::Vec3d(left_projection(0, 3), left_projection(1, 3), left_projection(2, 3));
  return x_rect + shift;
}

cv::Vec3d KittiRig::LeftCameraFromVelo(const cv::Vec3d& x_velo) const {
  const cv::Vec4d rect = rect_from_velo * cv::Vec4d(x_velo[0], x_velo[1], x_velo[2], 1.0);
  return LeftCameraFromRect(cv::Vec3d(rect[0], rect[1], rect[2]));
}

cv::Point2d KittiRig::Project(const cv::Vec3d& x_in_left) const {
  const cv::Vec3d x = K() * x_in_left;
  return cv::Point2d(x[0] / x[2], x[1] / x[2]);
}

KittiRig ReadKittiRawCalibration(const std::string& date_folder, cv::Size size) {
  const std::string cam_path = (fs::path(date_folder) / "calib_cam_to_cam.txt").string();
  std::error_code error;
  if (!fs::is_regular_file(cam_path, error)) {
    throw InputError(cam_path +
                     ": missing (a KITTI raw drive's calibration lies in its date "
                     "folder, beside the drive folder)");
  }
  const CalibrationText cam(cam_path);
  if (size.area() == 0) {
    const std::vector<double> s = cam.Numbers("S_rect_02", 2);
    size = cv::Size(static_cast<int>(std::lround(s[0])), static_cast<int>(std::lround(s[1])));
  }
  const cv::Mat left = cam.Matrix("P_rect_02", 3, 4);
  KittiRig rig = MakeRig(cam_path, left, cam.Matrix("P_rect_03", 3, 4), size);
  const cv::Mat rect = cam.Matrix("R_rect_00", 3, 3);
  const std::string velo_path = (fs::path(date_folder) / "calib_velo_to_cam.txt").string();
  if (fs::is_regular_file(velo_path, error)) {
    const CalibrationText velo(velo_path);
    const cv::Matx44d cam_from_velo = Transform(velo.Matrix("R", 3, 3), velo.Matrix("T", 3, 1));
    rig.rect_from_velo = Transform(rect, cv::Mat::zeros(3, 1, CV_64F)) * cam_from_velo;
    rig.velo_source = velo_path;
  }
  return rig;
}

KittiRig ReadKittiFrameCalibration(const std::string& path, cv::Size size) {
  std::error_code error;
  if (!fs::is_regular_file(path, error))
    throw InputError(path + ": missing (the KITTI calibration)");
  const CalibrationText file(path);
  const cv::Mat left = file.Matrix("P2", 3, 4);
  KittiRig rig = MakeRig(path, left, file.Matrix("P3", 3, 4), size);
  // The tracking set names them R_rect and Tr_velo_cam, the object set R0_rect and
  // Tr_velo_to_cam.
  const std::string rect_key = file.FirstOf({"R_rect", "R0_rect"});
  const std::string velo_key = file.FirstOf({"Tr_velo_cam", "Tr_velo_to_cam"});
  if (rect_key.empty()) throw InputError(path + ": R_rect (R0_rect) is missing");
  if (velo_key.empty()) throw InputError(path + ": Tr_velo_cam (Tr_velo_to_cam) is missing");
  const cv::Mat velo = file.Matrix(velo_key, 3, 4);
  rig.rect_from_velo = Transform(file.Matrix(rect_key, 3, 3), cv::Mat::zeros(3, 1, CV_64F)) *
                       Transform(velo.colRange(0, 3), velo.col(3));
  rig.velo_source = path;
  return rig;
}

}  // namespace attend
