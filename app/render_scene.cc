#include "app/render_scene.h"

#include "synth/scene.h"
#include "util/timer.h"

namespace attend {

RenderSceneResult RenderScene(const RenderSceneRequest& request) {
  const Scene scene = LoadScene(request.scene);
  SynthOptions options;
  options.seed = request.seed;
  options.frames = request.frames;
  options.overwrite = request.overwrite;
  RenderSceneResult result;
  const Stopwatch watch;
  result.summary = RenderSequence(scene, request.out, options);
  result.milliseconds = watch.ElapsedMs();
  return result;
}

}  // namespace attend
