// Pieces of the command lines that several subcommands share.
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "util/frame_range.h"

namespace attend {

// `--set KEY=VALUE`, repeatable, one value per --set (so that positional arguments may follow
// it, and `--set a=1 b=2` is a mistake rather than two overrides).
CLI::Option* AddSetOption(CLI::App* command, std::vector<std::string>* sets,
                          const std::string& help);


// The output stem of every image, in order. Two images with one stem would overwrite each
// other's files: a ConfigError naming both and `outputs` (with STEM standing for the stem).
std::vector<std::string> OutputStems(const std::vector<std::string>& images,
                                     const std::string& outputs);

}  // namespace attend
