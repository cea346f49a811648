// The `inputs:` of a sweep file (docs/SWEEPS.md), and the sweep's source kinds: which key names
// an input's source, and how a cell's command takes it (SourceArguments, the one place that
// maps a sweep input to the source of `attend run` and `attend track`).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "app/sweep_plan.h"
#include "config/yaml_document.h"

namespace attend {

// Reads and checks the `inputs:` list: each entry's source exists and suits `command`, its
// ground truth is there, and the names are unique. Scene inputs get the folder they render
// into below `dir` (SWEEP_DIR when ""), not rendered.
std::vector<SweepInput> ReadSweepInputs(const YamlDocument& document, SweepCommand command,
                                        const std::string& dir);

// The words of `attend run` (and `attend track`) that name the input's source: `--sequence
// PATH`, `--left PATH --right PATH`, ... A rendered scene is a sequence.
std::vector<std::string> SourceArguments(const SweepInput& input);

// Letters, digits and . _ = + - kept; any other run of bytes becomes one '-'; at most
// `max_length` long. The names of inputs and cells.
std::string FileSafe(const std::string& text, std::size_t max_length);

}  // namespace attend
