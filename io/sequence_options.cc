#include "io/sequence_options.h"

#include <utility>

namespace attend {

const std::vector<std::string>& SequenceOptions::ResizeModes() {
  static const std::vector<std::string> modes = {"fit", "pixels", "stretch", "native"};
  return modes;
}

const OptionFields<SequenceOptions>& SequenceOptions::Fields() {
  using O = SequenceOptions;
  static const OptionFields<SequenceOptions> fields = {
      {"first_frame", &O::first_frame, Range::Closed(0, 1e9), "first frame of the range"},
      {"last_frame", &O::last_frame, Range::Closed(-1, 1e9),
       "last frame of the range, inclusive; -1: to the end"},
      {"stride", &O::stride, Range::Closed(1, 1e6), "take every n-th frame of the range"},
      {"width", &O::width, Range::AboveUpTo(0, 16384), "working width, px"},
      {"height", &O::height, Range::AboveUpTo(0, 16384), "working height, px"},
      {"resize", &O::resize, "fit: keep the aspect ratio within width x height; pixels: keep the aspect ratio with width x height pixels; stretch: exactly; native: no scaling",
       &SequenceOptions::ResizeModes},
      {"check_rows", &O::check_rows,
       "refuse a stereo pair whose first frame's rows do not match (not rectified)"}};
  return fields;
}

std::string SequenceOptions::Check() const {
  // In the order of the keys: the source's kinds and ranges, the range's and size's ranges,
  // then the live keys.
  std::string error = source.CheckKinds();
  if (!error.empty()) return error;
  // The working size is checked below, and only unless resize is native.
  SequenceOptions sized = *this;
  sized.width = SequenceOptions().width;
  sized.height = SequenceOptions().height;
  error = CheckFieldRanges(sized, Fields());
  if (!error.empty()) return error;
  error = source.CheckLive();
  if (!error.empty()) return error;
  if (last_frame != -1 && last_frame < first_frame) {
    return "last_frame must be -1 (to the end) or >= first_frame (" + std::to_string(first_frame) +
           "), got " + std::to_string(last_frame);
  }
  if (resize != "native") {
    for (const auto& [name, side] :
         {std::pair<const char*, int>{"width", width}, {"height", height}}) {
      const Range& range = RangeOf(Fields(), name);
      if (!range.Contains(side)) {
        return std::string(name) + " " + range.DescribeBreach(side) +
               " unless resize is native, got " + std::to_string(side);
      }
    }
  }
  return "";
}

}  // namespace attend
