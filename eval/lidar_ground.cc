#include "eval/lidar_ground.h"

#include <cmath>

#include "util/error.h"

namespace attend {

namespace {

constexpr double kPi = 3.14159265358979323846;

// The plane through three points, oriented up; false when they are (nearly) collinear.
bool PlaneThrough(const cv::Vec3d& a, const cv::Vec3d& b, const cv::Vec3d& c, LidarGroundPlane* plane) {
  cv::Vec3d n = (b - a).cross(c - a);
  const double length = cv::norm(n);
  if (length < 1e-9) return false;
  n /= length;
  if (n[1] > 0) n = -n;
  plane->normal = n;
  plane->offset = -n.dot(a);
  return true;
}

// The least-squares plane of the points within `tolerance` of `plane`: through their centroid,
// normal along the covariance's smallest eigenvector. `plane` unchanged when fewer than 3.
void Refit(const std::vector<cv::Vec3d>& points, double tolerance, LidarGroundPlane* plane) {
  std::vector<cv::Vec3d> inliers;
  for (const cv::Vec3d& p : points) {
    if (plane->Distance(p) < tolerance) inliers.push_back(p);
  }
  if (inliers.size() < 3) return;
  cv::Vec3d centroid(0, 0, 0);
  for (const cv::Vec3d& p : inliers) centroid += p;
  centroid /= static_cast<double>(inliers.size());
  cv::Matx33d covariance = cv::Matx33d::zeros();
  for (const cv::Vec3d& p : inliers) {
    const cv::Vec3d d = p - centroid;
    covariance += d * d.t();
  }
  cv::Mat values, vectors;
  cv::eigen(cv::Mat(covariance), values, vectors);  // descending: the last row is the normal
  cv::Vec3d n(vectors.at<double>(2, 0), vectors.at<double>(2, 1), vectors.at<double>(2, 2));
  if (n[1] > 0) n = -n;
  plane->normal = n / cv::norm(n);
  plane->offset = -plane->normal.dot(centroid);
}

int CountWithin(const std::vector<cv::Vec3d>& points, const LidarGroundPlane& plane, double tolerance) {
  int count = 0;
  for (const cv::Vec3d& p : points) count += plane.Distance(p) < tolerance ? 1 : 0;
  return count;
}

}  // namespace

std::string LidarGroundOptions::Check() const {
  if (!(max_tilt_deg > 0 && max_tilt_deg < 90)) return "max_tilt_deg must be in (0, 90)";
  if (!(ransac_tolerance_m > 0)) return "ransac_tolerance_m must be > 0";
  if (iterations < 1) return "iterations must be >= 1";
  if (min_points < 3) return "min_points must be >= 3";
  if (!(max_depth_m > 0)) return "max_depth_m must be > 0";
  return "";
}

LidarGroundPlane FitLidarGroundPlane(const std::vector<cv::Vec3d>& points,
                           const LidarGroundOptions& options) {
  ATTEND_CHECK(options.Check().empty()) << "ground plane options: " << options.Check();
  // Candidates: below the camera (Y down) and near enough.
  std::vector<cv::Vec3d> below;
  for (const cv::Vec3d& p : points) {
    if (p[1] > 0 && p[2] < options.max_depth_m) below.push_back(p);
  }
  LidarGroundPlane best;
  if (static_cast<int>(below.size()) < options.min_points) return best;
  const double min_cos = std::cos(options.max_tilt_deg * kPi / 180.0);
  cv::RNG rng(static_cast<uint64_t>(options.seed));
  const int n = static_cast<int>(below.size());
  for (int i = 0; i < options.iterations; ++i) {
    const int a = rng.uniform(0, n), b = rng.uniform(0, n), c = rng.uniform(0, n);
    if (a == b || b == c || a == c) continue;
    LidarGroundPlane plane;
    if (!PlaneThrough(below[a], below[b], below[c], &plane)) continue;
    if (-plane.normal[1] < min_cos) continue;  // too steep to be the road
    plane.inliers = CountWithin(below, plane, options.ransac_tolerance_m);
    if (plane.inliers > best.inliers) best = plane;
  }
  if (best.inliers < 3) return LidarGroundPlane{};
  LidarGroundPlane refined = best;
  Refit(below, options.ransac_tolerance_m, &refined);
  // The refit keeps the level constraint; one that tilts away (few inliers on a wall's foot)
  // leaves the sampled plane.
  if (-refined.normal[1] >= min_cos) best = refined;
  best.found = true;
  best.inliers = CountWithin(points, best, kGroundPlaneToleranceM);
  return best;
}

HorizonLine HorizonOfPlane(const cv::Vec3d& normal, const cv::Matx33d& K) {
  const cv::Vec3d line = K.inv().t() * normal;
  HorizonLine horizon;
  horizon.a = line[0];
  horizon.b = line[1];
  horizon.c = line[2];
  return horizon;
}

LidarTruth ProjectScan(const std::vector<cv::Vec4f>& scan, const KittiRig& rig, cv::Size size,
                       const LidarGroundOptions& options) {
  if (rig.velo_source.empty()) {
    throw InputError(rig.stereo.source +
                     ": the rig has no Velodyne pose (calib_velo_to_cam.txt "
                     "is missing beside it), so its scans cannot be placed");
  }
  LidarTruth truth;
  std::vector<cv::Vec3d> in_camera;
  for (const cv::Vec4f& p : scan) {
    if (!(p[0] > 0.f)) continue;  // behind the Velodyne (and NaN)
    const cv::Vec3d x = rig.LeftCameraFromVelo(cv::Vec3d(p[0], p[1], p[2]));
    if (!(x[2] > kMinPointDepthM)) continue;
    const cv::Point2d pixel = rig.Project(x);
    if (pixel.x < 0 || pixel.y < 0 || pixel.x >= size.width || pixel.y >= size.height) continue;
    in_camera.push_back(x);
    TruthPoint point;
    point.u = static_cast<float>(pixel.x);
    point.v = static_cast<float>(pixel.y);
    point.depth_m = static_cast<float>(x[2]);
    truth.points.push_back(point);
  }
  truth.plane = FitLidarGroundPlane(in_camera, options);
  if (!truth.plane.found) return truth;
  for (size_t i = 0; i < in_camera.size(); ++i) {
    truth.points[i].ground = truth.plane.Distance(in_camera[i]) < kGroundPlaneToleranceM;
  }
  truth.horizon = HorizonOfPlane(truth.plane.normal, rig.K());
  return truth;
}

}  // namespace attend
