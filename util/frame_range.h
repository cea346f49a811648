// The frame range of `--frames FIRST:LAST`, which several commands and controllers take.
#pragma once

#include <string>

namespace attend {

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

}  // namespace attend
