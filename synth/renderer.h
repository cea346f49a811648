// Analytic rendering of a synthetic stereo scene with exact ground truth (docs/SYNTH.md).
// Every pixel is sampled at its centre (integer coordinates) in continuous image coordinates,
// so non-integer disparities and sizes are exact; no image resampling is involved.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <opencv2/core.hpp>
#include <vector>

#include "io/ground_truth.h"
#include "synth/rendered_frame.h"
#include "synth/scene.h"

namespace attend {

class StreetRenderer;

// Renders a scene; a street scene (Scene::street) through its StreetRenderer.
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
  std::shared_ptr<const StreetRenderer> street_;    // street scenes only
};

}  // namespace attend
