#include "app/run_attention.h"

#include <filesystem>

#include "app/home.h"
#include "pipeline/options_io.h"
#include "util/error.h"
#include "util/frame_range.h"

namespace attend {

AttendOptions ResolveRunOptions(const AttentionRunRequest& request) {
  const std::string config_path = request.config.empty() ? DefaultConfigPath() : request.config;
  AttendOptions options = LoadOptions(config_path, request.sets);
  SequenceOptions& sequence = options.sequence;
  const SourceSpec& source = request.source;
  if (!source.empty()) {
    // How a live source is read (queue, timeouts) stays the configuration's.
    const LiveOptions live = sequence.source.live;
    sequence.source = source;
    sequence.source.live = live;
    sequence.source.live.side_by_side = source.live.side_by_side;
  }
  // Alone, it applies to the configuration's live source.
  if (source.live.side_by_side) sequence.source.live.side_by_side = true;
  // --calib applies to the source given with it, or alone to the configuration's.
  if (!source.calib.empty()) sequence.source.calib = source.calib;
  if (request.duration_s >= 0.0) {
    if (!sequence.source.IsLive()) {
      throw ConfigError("--duration bounds a live source (--camera, --gst, or the "
                        "configuration's sequence.camera or sequence.gst); the source is " +
                        (sequence.source.empty() ? std::string("the bundled sequence")
                                                 : sequence.source.Describe()));
    }
    sequence.source.live.duration_s = request.duration_s;
  }
  if (!request.frames.empty()) {
    const FrameRange range =
        ParseFrameRange(request.frames, {sequence.first_frame, sequence.last_frame});
    sequence.first_frame = range.first;
    sequence.last_frame = range.last;
  }
  if (sequence.source.empty()) sequence.source.folder = EnsureBundledSequence(request.quiet);
  for (std::string* path : sequence.source.Paths()) {
    if (!path->empty()) *path = std::filesystem::absolute(*path).lexically_normal().string();
  }
  return options;
}

std::vector<std::string> RunSourceArguments(const SourceSpec& source) {
  std::vector<std::string> arguments;
  auto add = [&](const char* flag, const std::string& value) {
    if (!value.empty()) arguments.insert(arguments.end(), {flag, value});
  };
  add("--sequence", source.folder);
  add("--left", source.left_video);
  add("--right", source.right_video);
  add("--side-by-side", source.side_by_side_video);
  add("--video", source.video);
  add("--images", source.images);
  if (source.camera >= 0) add("--camera", std::to_string(source.camera));
  if (source.camera_right >= 0) add("--camera-right", std::to_string(source.camera_right));
  add("--gst", source.gst);
  add("--gst-right", source.gst_right);
  add("--calib", source.calib);
  if (source.live.side_by_side) arguments.push_back("--side-by-side-live");
  return arguments;
}

bool ShippedFeatures(const AttentionRunRequest& request) {
  if (!request.config.empty()) {
    std::error_code error;
    if (!std::filesystem::equivalent(request.config, DefaultConfigPath(), error)) return false;
  }
  for (const std::string& assignment : request.sets) {
    const std::string key = assignment.substr(0, assignment.find('='));
    if (key == "features" || key.rfind("features.", 0) == 0) return false;
  }
  return true;
}

RunSummary RunAttention(const AttentionRunRequest& request, const AttendOptions& options) {
  RunRequest run;
  run.options = options;
  run.overwrite = request.overwrite;
  run.config_path = request.config.empty() ? DefaultConfigPath() : request.config;
  run.command_line = request.command_line;
  run.home = AttendHome();
  // Empty: the run loop names a folder under runs/ once it knows the sequence's name.
  run.out_dir = !request.out.empty() ? request.out : run.options.output.dir;
  run.stop = request.stop;
  run.on_progress = request.on_progress;
  run.stereo_features_optional = ShippedFeatures(request);
  run.on_left_out = request.on_left_out;
  return RunSequence(run);
}

}  // namespace attend
