// Pieces of the command lines that several subcommands share.
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

namespace attend {

// `--set KEY=VALUE`, repeatable, one value per --set (so that positional arguments may follow
// it, and `--set a=1 b=2` is a mistake rather than two overrides).
CLI::Option* AddSetOption(CLI::App* command, std::vector<std::string>* sets,
                          const std::string& help);

// A frame range FIRST:LAST of --frames, inclusive; either side may be empty (`last` -1: to the
// end of the source).
struct FrameRange {
  int first = 0;
  int last = -1;
};

// Parses `text` of `--frames` over `range`: a side left empty keeps `range`'s value. A
// ConfigError naming the option and the text when it is not FIRST:LAST with non-negative
// integers, or the range ends before it starts.
FrameRange ParseFrameRange(const std::string& text, FrameRange range = FrameRange());

// The output stem of every image, in order. Two images with one stem would overwrite each
// other's files: a ConfigError naming both and `outputs` (with STEM standing for the stem).
std::vector<std::string> OutputStems(const std::vector<std::string>& images,
                                     const std::string& outputs);

}  // namespace attend
