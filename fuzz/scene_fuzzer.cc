// The scene files of `attend synth` (docs/SYNTH.md): the input is a scene, read in memory with
// ParseScene. A scene that reads is then asked what the renderer asks of it on every frame
// (the interpolated path of each object and the brightness), at the first, middle and last
// frame; nothing is rendered, since a valid scene may be 8192x8192.
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz/fuzz_support.h"
#include "synth/scene.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  attend::fuzz::Initialize();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace attend;
  fuzz::ExpectOnlyDocumentedErrors([&] {
    const Scene scene = ParseScene(fuzz::ToString(data, size), "fuzz_scene.yaml");
    for (const int frame : {0, scene.frames / 2, scene.frames - 1}) {
      InterpolateGain(scene.brightness, frame);
      for (const SceneObject& object : scene.objects) InterpolatePath(object.path, frame);
    }
  });
  return 0;
}
