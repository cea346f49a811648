// The controller of `attend synth` (SPEC 3.2, docs/SYNTH.md): a scene description rendered
// into a stereo sequence with exact ground truth. The command only parses its arguments and
// prints.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "synth/render_sequence.h"

namespace attend {

struct RenderSceneRequest {
  std::string scene;                  // the scene YAML (docs/SYNTH.md)
  std::string out;                    // the sequence folder
  std::optional<std::uint64_t> seed;  // replaces the scene's seed
  std::optional<int> frames;          // replaces the scene's frame count
  bool overwrite = false;             // replace a previous sequence's files in `out`
};

struct RenderSceneResult {
  SynthSummary summary;
  double milliseconds = 0.0;  // rendering and writing
};

// ConfigError naming the scene file and key for a bad scene; OutputError for a folder that
// cannot be written or holds a sequence without `overwrite`.
RenderSceneResult RenderScene(const RenderSceneRequest& request);

}  // namespace attend
