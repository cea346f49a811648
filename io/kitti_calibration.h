// A KITTI rig's calibration (the devkit's readme): the rectified projections of the colour pair
// (image_02 left, image_03 right), turned into the StereoCalibration a run's positions use,
// and the Velodyne's pose, which takes LiDAR points and 3D labels into the left image.
//
//   raw drive       DATE/calib_cam_to_cam.txt: S_rect_02, P_rect_02, P_rect_03, R_rect_00;
//                   DATE/calib_velo_to_cam.txt: R, T
//   tracking        calib/NNNN.txt: P2, P3, R_rect, Tr_velo_cam
//   object          calib/NNNNNN.txt: P2, P3, R0_rect, Tr_velo_to_cam
//
// The projections map camera 0's rectified frame to the image: x = P_rect_02 R_rect_00
// Tr_velo_to_cam X_velo (devkit, raw data readme).
#pragma once

#include <opencv2/core.hpp>
#include <string>

#include "io/stereo_calibration.h"

namespace attend {

struct KittiRig {
  StereoCalibration stereo;     // the rectified colour pair, at the frames' size
  cv::Matx34d left_projection;  // P_rect_02 (P2): camera 0's rectified frame to the left image
  cv::Matx44d rect_from_velo = cv::Matx44d::eye();  // R_rect_00 Tr_velo_to_cam
  // The file that gave the Velodyne's pose; "" when the rig has none (a raw drive without
  // calib_velo_to_cam.txt), and then LiDAR points and tracklets cannot be placed.
  std::string velo_source;

  // The left colour camera's intrinsics (the left 3x3 of left_projection).
  cv::Matx33d K() const;
  // A point of camera 0's rectified frame (KITTI's labels' locations) in the left colour
  // camera's: shifted by K^-1 times P_rect_02's last column.
  cv::Vec3d LeftCameraFromRect(const cv::Vec3d& x_rect) const;
  // A Velodyne point in the left colour camera's rectified frame (X right, Y down, Z forward,
  // metres): camera 0's rectified frame shifted by K^-1 times P_rect_02's last column.
  cv::Vec3d LeftCameraFromVelo(const cv::Vec3d& x_velo) const;
  // A point of the left camera's frame in the left image's pixels (Z must be positive).
  cv::Point2d Project(const cv::Vec3d& x_in_left) const;
};

// A raw drive's rig from its date folder. `size`: the frames' size; empty takes S_rect_02.
// InputError naming the file and key that is missing or malformed; a missing
// calib_velo_to_cam.txt leaves velo_source empty.
KittiRig ReadKittiRawCalibration(const std::string& date_folder, cv::Size size);
// A tracking sequence's calib/NNNN.txt or an object frame's calib/NNNNNN.txt, for frames of
// `size` (neither file gives it). InputError naming the file and key.
KittiRig ReadKittiFrameCalibration(const std::string& path, cv::Size size);

}  // namespace attend
