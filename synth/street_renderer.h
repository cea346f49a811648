// Ray casting of a street scene (docs/SYNTH.md, "Street scenes"): a stereo camera at a height
// above a flat ground, pitched about its x axis and driving forward, sees the ground to the
// horizon, the sky above it, a row of facades at the end of the road and upright billboards
// standing on the ground. Every pixel's depth and class are exact by construction.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "synth/rendered_frame.h"
#include "synth/scene.h"

namespace attend {

// The horizon of a street scene in the left image, {a, b, c} of a u + b v + c = 0: the row
// cy - f tan(pitch), where cy = (height - 1) / 2 is the principal point's row (the calibration
// that attend synth writes puts the principal point at the image centre).
std::array<double, 3> StreetHorizon(const Scene& scene);

// The camera's distance along the road at `frame`: speed_mps * frame / fps.
double CameraDistance(const Scene& scene, int frame);

// Objects whose centre is nearer than this to the camera (in its depth) have been passed: they
// are not drawn and have no ground-truth row.
inline constexpr double kPassedDepthM = 1.0;

class StreetRenderer final {
 public:
  // `scene` has a street block and passes Check().
  explicit StreetRenderer(Scene scene);

  // Renders frame `frame` (>= 0), independently of any other frame.
  RenderedFrame Render(int frame) const;

 private:
  Scene scene_;
  std::uint64_t ground_key_ = 0, sky_key_ = 0, backdrop_key_ = 0;
  std::vector<std::uint64_t> texture_keys_;  // per object, in scene order
};

}  // namespace attend
