// The controller of `attend track-detections`: the detector-alone peer of `attend run`
// (docs/ATTENTION.md, "The detector-alone peer"). It runs only the configuration's top-down
// channel (the feature named `feature`, `people` by default: one whose FeatureMap reports
// detections) on every frame of the same source at the same working size as `attend run`,
// searching the whole frame every frame, links its detections into tracks
// (app/detection_tracks.h) and writes a run folder that `attend eval` scores as it scores an
// `attend run` folder: config.yaml, frames.jsonl (one record a frame, each track in the frames
// a detection continued it, in input pixels) and summary.json (with the `detectors` block of
// `attend run`). No attention: what it scores is the detector and the simplest tracking on top.
#pragma once

#include <string>

#include "app/detection_tracks.h"
#include "app/run_attention.h"

namespace attend {

struct DetectionTracksRequest {
  // The configuration, its overrides, the source, the frames, the run folder, --overwrite and
  // the progress callback, as `attend run` takes them (ResolveRunOptions). The stop flag
  // finishes the frame and closes the run as an interrupted one; on_left_out is not used.
  AttentionRunRequest run;
  std::string feature = "people";  // the top-down channel's name in `features:`
  DetectionLinkOptions link;
};

// The configuration the peer runs with: ResolveRunOptions of `request.run` with the channel
// made to search the whole frame every frame (its `gate: frame` and `every: 1` set after the
// overrides), and only that channel in `features`. A configuration without an enabled feature
// of that name: ConfigError naming it and the file (exit status 2); other errors as
// ResolveRunOptions's.
AttendOptions ResolveDetectorOptions(const DetectionTracksRequest& request);

// Runs the channel and the linker over the source into the run folder and returns its summary
// (targets_attended: the tracks started). Before the first frame: ConfigError for a feature
// that reports no detections, a missing model file or a folder that is not empty (without
// --overwrite), InputError for a source that cannot be read. A bad frame later keeps the
// frames done, writes summary.json with the error and rethrows, as `attend run` does.
RunSummary TrackDetections(const DetectionTracksRequest& request, const AttendOptions& options);

}  // namespace attend
