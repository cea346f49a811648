// The `live:` section of the configuration (docs/LIVE.md): how a live source (a V4L2 camera or
// a GStreamer pipeline, SourceSpec::camera and gst) is read, and what a live run reports
// about it. Kept apart from io/live_source.h so that io/source_spec.h can hold it without seeing
// the capture code.
#pragma once

#include <string>

#include "util/option_fields.h"

namespace attend {

struct LiveOptions {
  // Frames held between the capture thread and the loop. When the loop is slower than the
  // source, the oldest frame is dropped (and counted) to make room: a small queue keeps the
  // latency low, a larger one rides out a slow frame.
  int queue = 2;
  // A live source that delivers no frame for this long has stopped: the run ends with the
  // frames it had (and fails to open when the first frame does not come within it), s.
  double timeout_s = 5.0;
  // Stop capturing this long after the first frame was captured (the frames already queued are
  // still processed); 0: no bound (the frame range, the end of the stream or Ctrl-C ends it), s.
  double duration_s = 0.0;
  // The one live source (camera or gst) holds the left view in the left half of each frame and
  // the right view in the right half, as a side-by-side stereo camera does.
  bool side_by_side = false;

  static const OptionFields<LiveOptions>& Fields();
};

// How a live source ended, for summary.json ("live": "end") and the terminal.
enum class LiveEnd {
  kRunning,      // not ended (yet)
  kEndOfStream,  // the source said it has no more frames (a finite GStreamer pipeline's EOS)
  kFrameRange,   // the frame range's last frame was captured (sequence.last_frame, --frames)
  kDuration,     // live.duration_s passed
  kTimeout,      // no frame for live.timeout_s: the source stopped delivering
  kStopped,      // the run stopped taking frames (Ctrl-C, an error) while the source went on
  kError,        // reading the source failed
};

// "end of stream", "frame range", "duration", "timeout", "stopped", "error" ("running").
const char* LiveEndName(LiveEnd end);

// What a live source reports about its capture. Frames are counted from the range's first
// frame, stride applied: captured = handed out + dropped + unprocessed.
struct LiveStatus {
  std::string source;     // SourceSpec::Describe()
  int queue = 0;          // the queue's capacity (live.queue)
  int captured = 0;       // frames read from the source (of the range)
  int dropped = 0;        // the oldest frames dropped from a full queue: the loop was slower
  int unprocessed = 0;    // frames still queued when the run stopped taking them
  LiveEnd end = LiveEnd::kRunning;
  std::string why;        // a sentence on how it ended, naming the source
};

}  // namespace attend
