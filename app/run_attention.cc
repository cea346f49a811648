#include "app/run_attention.h"

#include <filesystem>

#include "app/home.h"
#include "pipeline/options_io.h"
#include "util/frame_range.h"

namespace attend {

AttendOptions ResolveRunOptions(const AttentionRunRequest& request) {
  const std::string config_path = request.config.empty() ? DefaultConfigPath() : request.config;
  AttendOptions options = LoadOptions(config_path, request.sets);
  SequenceOptions& sequence = options.sequence;
  const RunSource& source = request.source;
  if (!source.folder.empty() || !source.left_video.empty() ||
      !source.side_by_side_video.empty() || !source.video.empty() || !source.images.empty()) {
    sequence.folder = source.folder;
    sequence.left_video = source.left_video;
    sequence.right_video = source.right_video;
    sequence.side_by_side_video = source.side_by_side_video;
    sequence.video = source.video;
    sequence.images = source.images;
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
  return RunSequence(run);
}

}  // namespace attend
