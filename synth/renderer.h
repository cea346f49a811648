// Analytic rendering of a synthetic stereo scene with exact ground truth (docs/SYNTH.md).
// Every pixel is sampled at its centre (integer coordinates) in continuous image coordinates,
// so non-integer disparities and sizes are exact; no image resampling is involved.
#pragma once

#include <array>
#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

#include "io/ground_truth.h"
#include "synth/scene.h"

namespace attend {

// One rendered frame and its ground truth.
struct RenderedFrame {
  int frame = 0;
  cv::Mat left;       // CV_8UC3, BGR
  cv::Mat right;      // CV_8UC3, BGR
  cv::Mat disparity;  // CV_32FC1, left view, pixels: focal_px * baseline_m / Z of what is seen
  cv::Mat left_ids;   // CV_32SC1, id of the object seen at each left pixel, 0 for background
  cv::Mat right_ids;  // CV_32SC1, the same for the right view
  // One entry per object present in this frame (entry <= frame <= exit), by increasing id;
  // hidden objects have visible_fraction 0 and an empty box at (0, 0).
  std::vector<GtObject> objects;
};

class SceneRenderer final {
 public:
  // Throws ConfigError when scene.Check() fails.
  explicit SceneRenderer(Scene scene);

  const Scene& scene() const { return scene_; }

  // Renders frame `frame` (>= 0; frames beyond scene().frames continue the paths). Frames are
  // independent: rendering them in any order gives the same bytes.
  RenderedFrame Render(int frame) const;

 private:
  Scene scene_;
  std::uint64_t background_key_ = 0;
  std::vector<std::uint64_t> texture_keys_;         // per object, in scene order
  std::vector<std::array<double, 2>> blob_phases_;  // per object, radians
};

}  // namespace attend
