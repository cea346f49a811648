// The `inputs:` of a sweep file (docs/SWEEPS.md), and the sweep's source kinds: which key names
// an input's source, and how a cell's command takes it (SourceArguments, the one place that
// maps a sweep input to the source of `attend run` and `attend track`).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "config/yaml_document.h"
#include "io/source_spec.h"

namespace attend {

// What each cell runs: `attend run` scored by `attend eval`, `attend track` scored by
// `attend eval-tracking`, or `attend saliency` scored by `attend eval-fixations`.
enum class SweepCommand { kRun, kTrack, kSaliency };

const char* SweepCommandName(SweepCommand command);

struct SweepInput {
  std::string name;  // unique among the inputs; part of the cells' folder names
  // sequence, video, images, left (with right), side_by_side, fixations, or scene (a scene
  // file rendered once into the sweep folder's scenes/, then a sequence); app/sweep_inputs.h
  std::string kind;
  std::string path;   // absolute; for a scene, the sequence it renders into
  std::string scene;  // a scene's file
  std::string right;  // the right video of a left/right pair
  std::string gt;     // run: a gt/ folder; track: an OTB groundtruth_rect.txt; "" the default
  std::string frames;  // FIRST:LAST, "" for all
  int skip = 0;        // fixations: leave out the first N images (by id) ...
  int first = 0;       // ... and take the next N (0: all)
  std::string where;   // "FILE:LINE" of its entry
};

// Reads and checks the `inputs:` list: each entry's source exists and suits `command`, its
// ground truth is there, and the names are unique. Scene inputs get the folder they render
// into below `dir` (SWEEP_DIR when ""), not rendered.
std::vector<SweepInput> ReadSweepInputs(const YamlDocument& document, SweepCommand command,
                                        const std::string& dir);

// The input's source as the run takes it (io/source_spec.h): a rendered scene is the sequence
// folder it renders into; fixations inputs have none.
SourceSpec InputSource(const SweepInput& input);

// The words of `attend run` (and `attend track`) that name the input's source: `--sequence
// PATH`, `--left PATH --right PATH`, ... (RunSourceArguments of InputSource).
std::vector<std::string> SourceArguments(const SweepInput& input);

// Letters, digits and . _ = + - kept; any other run of bytes becomes one '-'; at most
// `max_length` long. The names of inputs and cells.
std::string FileSafe(const std::string& text, std::size_t max_length);

}  // namespace attend
