// Where attention lands (SPEC 4, "Where attention lands"): the ground truth of a frame's
// scene, whatever it came from. A KITTI drive gives it from its LiDAR scans and 3D labels
// (io/kitti_*.h); a rendered street scene from its exact per-pixel classes and disparities
// (gt/classes/, gt/disparity/, sequence.yaml's focal_px and baseline_m). Both are reduced to
// the same points and boxes, so that one set of definitions (eval/landing.h) scores both.
//
// Everything is in the pixels of the input frames, as frames.jsonl is.
#pragma once

#include <limits>
#include <map>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace attend {

// A pixel whose depth is known: a LiDAR point projected into the left image, or a pixel of a
// rendered scene with a disparity. `ground`: the point lies on the frame's ground plane (within
// kGroundPlaneToleranceM of it for a LiDAR scan; the rendered ground class for a scene).
struct TruthPoint {
  float u = 0.f, v = 0.f;  // input pixels of the left image
  float depth_m = 0.f;     // Z in the left (rectified) camera's frame, metres; > 0
  bool ground = false;
};

// A labelled object visible in a frame (a KITTI tracklet or label projected into the left image
// and clipped to it, or a rendered object's visible box).
struct TruthObject {
  int id = 0;
  cv::Rect2d box;       // input pixels
  std::string kind;     // "Car", "Cyclist", "Pedestrian", "person", ...
  double depth_m = std::numeric_limits<double>::quiet_NaN();  // its centre's Z, when known
};

// The horizon: the image line of the ground plane's vanishing points, a u + b v + c = 0 with
// b != 0. A pixel is above the horizon when its v is less than HorizonV(u). Not set (b = 0)
// when the frame gives no ground plane.
struct HorizonLine {
  double a = 0.0, b = 0.0, c = 0.0;
  bool valid() const { return b != 0.0; }
  double HorizonV(double u) const { return -(a * u + c) / b; }
};

struct FrameTruth {
  int frame = 0;
  cv::Size image_size;                // input pixels
  std::vector<TruthObject> objects;   // labelled objects in view in this frame
  std::vector<TruthPoint> points;     // pixels with known depth (none on the sky)
  HorizonLine horizon;
};

// The scene truth of a sequence, by frame index.
using SceneTruth = std::map<int, FrameTruth>;

// A LiDAR point is on the ground plane when it lies within this many metres of it (the bar's
// definition, issue 55).
inline constexpr double kGroundPlaneToleranceM = 0.3;

}  // namespace attend
