// Writing a rendered scene as a stereo sequence folder in the SPEC 3.1 layout.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "synth/scene.h"

namespace attend {

struct SynthOptions {
  std::optional<std::uint64_t> seed;  // replaces the scene's seed
  std::optional<int> frames;          // replaces the scene's frame count; >= 1
  // Write into a non-empty folder, replacing only the layout's own files and folders
  // (left/, right/, gt/disparity/, gt/classes/, gt/horizon.txt, gt/objects.csv, calib.yaml,
  // sequence.yaml); anything else is kept.
  bool overwrite = false;
  // Threads that render and write frames; 0: one per hardware thread. The files do not
  // depend on it.
  int threads = 0;

  // "" when valid; otherwise names the field and the broken constraint.
  std::string Check() const;
};

struct SynthSummary {
  int frames = 0;          // frames written
  int objects = 0;         // objects in the scene
  std::uint64_t seed = 0;  // the seed used
  std::string path;        // the sequence folder

  // "wrote 120 frames of 8 objects (seed 7) to SEQ".
  std::string BriefReport() const;
};

// Renders every frame of `scene` (with the options' overrides) and writes:
//   OUT/left/NNNNNN.png, OUT/right/NNNNNN.png      8-bit BGR views
//   OUT/gt/disparity/NNNNNN.pfm                    left-view disparity, pixels
//   OUT/gt/objects.csv                             one row per object per frame present
//   OUT/gt/classes/NNNNNN.png, OUT/gt/horizon.txt  street scenes: pixel classes, the horizon
//   OUT/sequence.yaml                              name, fps, focal_px, baseline_m, ...
// Frames are rendered and written in parallel; the same scene and seed give byte-identical
// files. A non-empty OUT without `overwrite`,
// invalid options or scene: ConfigError naming it. A file that cannot be written: InputError.
SynthSummary RenderSequence(const Scene& scene, const std::string& out_folder,
                            const SynthOptions& options);

}  // namespace attend
