// One rendered frame of a synthetic scene and its exact ground truth (docs/SYNTH.md).
#pragma once

#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

#include "io/ground_truth.h"

namespace attend {

// What a pixel of a street scene shows (gt/classes/NNNNNN.png, docs/SYNTH.md).
enum class PixelClass : std::uint8_t { kUnknown = 0, kObject = 1, kGround = 2, kSky = 3, kOther = 4 };

// One rendered frame and its ground truth.
struct RenderedFrame {
  int frame = 0;
  cv::Mat left;       // CV_8UC3, BGR
  cv::Mat right;      // CV_8UC3, BGR
  // CV_32FC1, left view, pixels: focal_px * baseline_m / Z of what is seen; 0 (unknown) on the
  // sky of a street scene, which is infinitely far.
  cv::Mat disparity;
  cv::Mat left_ids;   // CV_32SC1, id of the object seen at each left pixel, 0 for background
  cv::Mat right_ids;  // CV_32SC1, the same for the right view
  // CV_8UC1, the PixelClass of each left pixel; street scenes only (empty otherwise).
  cv::Mat classes;
  // One entry per object present in this frame (entry <= frame <= exit), by increasing id;
  // hidden objects have visible_fraction 0 and an empty box at (0, 0).
  std::vector<GtObject> objects;
};

}  // namespace attend
