// Pieces of the command lines that several subcommands share.
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "pipeline/run.h"
#include "util/frame_range.h"

namespace attend {

// CLI::Range(min, max) that also refuses NaN (which compares false with both bounds, so that
// CLI::Range lets it through: `--duration nan` read as no bound) and infinities.
CLI::Validator FiniteRange(double min, double max);

// `--set KEY=VALUE`, repeatable, one value per --set (so that positional arguments may follow
// it, and `--set a=1 b=2` is a mistake rather than two overrides).
CLI::Option* AddSetOption(CLI::App* command, std::vector<std::string>* sets,
                          const std::string& help);

// The progress line of a run on stderr (`attend run`, `attend track-detections`): frames done,
// frames a second and the time left, rewritten in place at most ten times a second.
void PrintRunProgress(const RunProgress& progress);

// The output stem of every image, in order. Two images with one stem would overwrite each
// other's files: a ConfigError naming both and `outputs` (with STEM standing for the stem).
std::vector<std::string> OutputStems(const std::vector<std::string>& images,
                                     const std::string& outputs);

}  // namespace attend
