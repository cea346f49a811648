// Scenes the benchmarks share.
#pragma once

#include "synth/scene.h"

namespace attend::bench {

// `scene` at twice its size: every length in pixels doubles (image, focal length, paths,
// oscillations), so the picture is the same one at twice the resolution with twice the
// disparities (the lab scene at 640x480 for SPEC 5's memory and speed at that size).
inline Scene Doubled(Scene scene) {
  scene.width *= 2;
  scene.height *= 2;
  scene.focal_px *= 2.0;
  for (SceneObject& object : scene.objects) {
    for (PathKeyframe& key : object.path) {
      key.x *= 2.0;
      key.y *= 2.0;
    }
    object.oscillation.amplitude_x *= 2.0;
    object.oscillation.amplitude_y *= 2.0;
  }
  return scene;
}

}  // namespace attend::bench
