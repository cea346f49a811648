// The controller of `attend run` (SPEC 3.2, 3.3): the attention pipeline over a sequence into a
// run folder. It loads the configuration, resolves the source (the request's, else the
// configuration's, else the bundled sequence), names it absolutely so that RUN/config.yaml
// repeats the run from any folder, and runs the loop (pipeline/run.h). The command only
// parses its arguments, installs the signal handlers and prints.
#pragma once

#include <atomic>
#include <functional>
#include <string>
#include <vector>

#include "io/source_spec.h"
#include "pipeline/run.h"

namespace attend {

struct AttentionRunRequest {
  std::string config;              // the configuration file; "": DefaultConfigPath()
  std::vector<std::string> sets;   // key=value overrides, as --set
  // A source given beside the configuration (io/source_spec.h): when any is set (SourceSpec's
  // empty() is false) it replaces the configuration's whole source, but for the reading
  // settings of its `live` (queue, timeout_s, duration_s), which stay the configuration's.
  // live.side_by_side set alone applies to the configuration's live source, and so does calib
  // (--calib): set, it replaces the configuration's sequence.calib.
  SourceSpec source;
  std::string frames;              // FIRST:LAST over the configuration's range; "": as it is
  double duration_s = -1.0;        // live.duration_s (--duration); < 0: as the configuration says
  std::string out;                 // the run folder; "": output.dir, else one under runs/
  bool overwrite = false;
  bool quiet = false;              // no notice while the bundled sequence renders
  std::string command_line;        // recorded in the summary
  const std::atomic<bool>* stop = nullptr;              // finish the frame, then stop
  std::function<void(const RunProgress&)> on_progress;  // after every frame
  // A feature left out because it needs stereo and the source is monocular (only with the
  // shipped configuration, ShippedFeatures).
  std::function<void(const std::string& feature)> on_left_out;
};

// The `attend run` arguments that give `source`, in the command's flags: {"--sequence", FOLDER},
// {"--left", A, "--right", B}, {"--side-by-side", V}, {"--video", V}, {"--images", DIR},
// {"--camera", "0", "--camera-right", "1"}, {"--gst", P}, ..., {"--calib", FILE} when calib is
// set, then "--side-by-side-live" when
// live.side_by_side is set; none for no source. The reading settings of `live` have no flag (the
// configuration holds them). A sweep's cells run their inputs with these.
std::vector<std::string> RunSourceArguments(const SourceSpec& source);

// Whether `request` runs the shipped list of features: no configuration of the user's own
// (no --config, or --config naming the shipped configs/default.yaml itself) and no --set of
// `features` or a key below it. On a monocular source such a run leaves the features that need
// stereo out, with a note; a configuration of the user's own that asks for them is refused
// (SPEC 3.1).
bool ShippedFeatures(const AttentionRunRequest& request);

// The configuration `request` makes: loaded with its overrides, its source and frame range
// replaced as asked, the bundled sequence when there is no source, every source path absolute.
// ConfigError for a bad file, key or value.
AttendOptions ResolveRunOptions(const AttentionRunRequest& request);

// Runs `options` (ResolveRunOptions of `request`) as `request` says (RunSequence): the run
// folder's summary. Errors as RunSequence's. Resolving first lets a caller load the
// configuration and render the bundled sequence before it installs its signal handlers.
RunSummary RunAttention(const AttentionRunRequest& request, const AttendOptions& options);

}  // namespace attend
