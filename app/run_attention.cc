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
  const RunSource& source = request.source;
  if (!source.empty()) {
    sequence.folder = source.folder;
    sequence.left_video = source.left_video;
    sequence.right_video = source.right_video;
    sequence.side_by_side_video = source.side_by_side_video;
    sequence.video = source.video;
    sequence.images = source.images;
    sequence.camera = source.camera;
    sequence.camera_right = source.camera_right;
    sequence.gst = source.gst;
    sequence.gst_right = source.gst_right;
    sequence.live.side_by_side = source.side_by_side_live;
  }
  // Alone, it applies to the configuration's live source.
  if (source.side_by_side_live) sequence.live.side_by_side = true;
  if (request.duration_s >= 0.0) {
    if (!sequence.IsLive()) {
      throw ConfigError("--duration bounds a live source (--camera, --gst, or the "
                        "configuration's sequence.camera or sequence.gst); the source is " +
                        (sequence.SourceCount() == 0 ? std::string("the bundled sequence")
                                                     : sequence.Describe()));
    }
    sequence.live.duration_s = request.duration_s;
  }
  if (!request.frames.empty()) {
    const FrameRange range =
        ParseFrameRange(request.frames, {sequence.first_frame, sequence.last_frame});
    sequence.first_frame = range.first;
    sequence.last_frame = range.last;
  }
  if (sequence.SourceCount() == 0) sequence.folder = EnsureBundledSequence(request.quiet);
  for (std::string* path : {&sequence.folder, &sequence.left_video, &sequence.right_video,
                            &sequence.side_by_side_video, &sequence.video, &sequence.images}) {
    if (!path->empty()) *path = std::filesystem::absolute(*path).lexically_normal().string();
  }
  return options;
}

bool RunSource::empty() const {
  return folder.empty() && left_video.empty() && right_video.empty() &&
         side_by_side_video.empty() && video.empty() && images.empty() && camera < 0 &&
         camera_right < 0 && gst.empty() && gst_right.empty();
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
