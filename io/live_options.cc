#include "io/live_options.h"

namespace attend {

const OptionFields<LiveOptions>& LiveOptions::Fields() {
  using O = LiveOptions;
  static const OptionFields<LiveOptions> fields = {
      {"queue", &O::queue, Range::Closed(1, 64),
       "frames held for the loop; when full the oldest is dropped"},
      {"timeout_s", &O::timeout_s, Range::AboveUpTo(0, 3600),
       "no frame for this long ends the run: the source has stopped, s"},
      {"duration_s", &O::duration_s, Range::Closed(0, 1e7),
       "stop capturing this long after the first frame; 0: no bound, s"},
      {"side_by_side", &O::side_by_side,
       "the live source holds the left view in its left half, the right in its right half"}};
  return fields;
}

const char* LiveEndName(LiveEnd end) {
  switch (end) {
    case LiveEnd::kRunning:
      return "running";
    case LiveEnd::kEndOfStream:
      return "end of stream";
    case LiveEnd::kFrameRange:
      return "frame range";
    case LiveEnd::kDuration:
      return "duration";
    case LiveEnd::kTimeout:
      return "timeout";
    case LiveEnd::kStopped:
      return "stopped";
    case LiveEnd::kError:
      return "error";
  }
  return "running";
}

}  // namespace attend
