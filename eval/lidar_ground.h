// A LiDAR scan as the truth of where attention lands (eval/scene_truth.h): its points projected
// into the left image with their depth, the frame's ground plane fitted to them, the points on
// it flagged, and the horizon that plane gives in the image.
#pragma once

#include <cmath>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "eval/scene_truth.h"
#include "io/kitti_calibration.h"

namespace attend {

// A plane n . X + offset = 0 in the left camera's frame (X right, Y down, Z forward), n a unit
// normal pointing up (n[1] < 0), so that offset is the camera's height above it.
struct LidarGroundPlane {
  bool found = false;
  cv::Vec3d normal{0.0, -1.0, 0.0};
  double offset = 0.0;
  int inliers = 0;  // the points within kGroundPlaneToleranceM of it

  double camera_height_m() const { return offset; }
  double Distance(const cv::Vec3d& x) const { return std::abs(normal.dot(x) + offset); }
};

// How the ground plane is searched for: RANSAC over the points below the camera, planes whose
// normal is within max_tilt_deg of the camera's Y axis, then a least-squares refit on the
// inliers. The seed makes it repeatable.
struct LidarGroundOptions {
  double max_tilt_deg = 20.0;       // the road's slope and the camera's pitch and roll together
  double ransac_tolerance_m = 0.1;  // a sample plane's inliers: the LiDAR's noise, a few cm
  int iterations = 300;             // enough to draw 3 road points when half the points are road
  int min_points = 30;              // fewer candidates than this: no plane
  double max_depth_m = 40.0;        // farther points are sparse and the road may bend
  int seed = 55;

  // Empty when valid; otherwise names the field and the broken constraint.
  std::string Check() const;
};

// The plane of `points` (in the left camera's frame) that most points lie on, under `options`;
// found = false when there are too few candidates or no sample plane is level enough.
LidarGroundPlane FitLidarGroundPlane(const std::vector<cv::Vec3d>& points,
                           const LidarGroundOptions& options = {});

// The horizon of the plane with normal `normal` (camera frame) in the image of intrinsics `K`:
// the vanishing line a u + b v + c = 0 with (a, b, c) = K^-T n (a direction d in the plane has
// n . d = 0 and images at x = K d).
HorizonLine HorizonOfPlane(const cv::Vec3d& normal, const cv::Matx33d& K);

// What a scan gives a frame: its points in the image (Z > kMinPointDepthM), flagged against
// the ground plane fitted to them, and the horizon.
struct LidarTruth {
  std::vector<TruthPoint> points;
  LidarGroundPlane plane;
  HorizonLine horizon;
};

// Points nearer than this are the car's own body or noise.
inline constexpr double kMinPointDepthM = 0.5;

// `scan` (Velodyne frame) through `rig` into the left image of `size`: the points ahead of the
// Velodyne (x > 0) that land inside the image at Z > kMinPointDepthM. InputError when the rig
// has no Velodyne pose.
LidarTruth ProjectScan(const std::vector<cv::Vec4f>& scan, const KittiRig& rig, cv::Size size,
                       const LidarGroundOptions& options = {});

}  // namespace attend
