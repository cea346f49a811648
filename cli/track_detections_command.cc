// attend track-detections: the detector-alone peer of `attend run` (app/track_detections.h;
// docs/ATTENTION.md, "The detector-alone peer"): the configuration's top-down channel on the
// whole frame every frame, its detections linked into tracks, written as a run folder that
// `attend eval` scores.
#include <unistd.h>

#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "app/track_detections.h"
#include "cli/cli_options.h"
#include "cli/commands.h"

namespace attend {

namespace {

struct TrackDetectionsArguments {
  std::string config;
  SourceSpec source;  // --sequence or --images
  std::string out;
  bool overwrite = false;
  std::vector<std::string> sets;
  std::string frames;
  bool quiet = false;
  std::string feature = "people";
  DetectionLinkOptions link;
  std::string command_line;
};

int TrackDetectionsCommand(const TrackDetectionsArguments& args) {
  DetectionTracksRequest request;
  request.run.config = args.config;
  request.run.sets = args.sets;
  request.run.source = args.source;
  request.run.frames = args.frames;
  request.run.out = args.out;
  request.run.overwrite = args.overwrite;
  request.run.quiet = args.quiet;
  request.run.command_line = args.command_line;
  request.feature = args.feature;
  request.link = args.link;
  const bool show_progress = !args.quiet && isatty(STDERR_FILENO);
  if (show_progress) request.run.on_progress = PrintRunProgress;
  const AttendOptions options = ResolveDetectorOptions(request);
  RunSummary summary;
  try {
    summary = TrackDetections(request, options);
  } catch (...) {
    if (show_progress) std::cerr << "\n";
    throw;
  }
  if (show_progress) std::cerr << "\n";
  if (!args.quiet) {
    std::cout << summary.BriefReport() << "\n"
              << summary.targets_attended << " tracks of '" << args.feature << "' detections"
              << std::endl;
  }
  return 0;
}

}  // namespace

void AddTrackDetectionsCommand(CLI::App& app, const std::string& command_line,
                               CommandAction* action) {
  auto args = std::make_shared<TrackDetectionsArguments>();
  CLI::App* command = app.add_subcommand(
      "track-detections",
      "The detector-alone peer of attend run (docs/ATTENTION.md, \"The detector-alone peer\"): "
      "runs only the configuration's top-down channel (--feature, default people) on the whole "
      "frame every frame, at attend run's working size, links its detections frame to frame "
      "(a constant-velocity prediction, a one-to-one match on IoU) and writes a run folder "
      "(config.yaml, frames.jsonl, summary.json) that attend eval scores like attend run's.");
  command->add_option("--config", args->config, "Configuration YAML with the channel")->required();
  auto* sequence = command->add_option("--sequence", args->source.folder,
                                       "Sequence folder with left/ (a right/ view is not used)");
  auto* images = command->add_option(
      "--images", args->source.images,
      "Monocular plain folder of frames (.png .jpg .jpeg .ppm .pgm, sorted by name)");
  sequence->excludes(images);
  command->add_option("--out", args->out, "Run folder")->required();
  command->add_flag("--overwrite", args->overwrite, "Replace a previous run in a non-empty --out");
  AddSetOption(command, &args->sets,
               "Override a configuration key, the value parsed as YAML, as for attend run; the "
               "channel's gate and every are then set to frame and 1");
  command->add_option("--frames", args->frames,
                      "Frame range FIRST:LAST, inclusive (10:50, 10:, :99)");
  command->add_flag("--quiet", args->quiet, "No progress line or report; errors only");
  command
      ->add_option("--feature", args->feature,
                   "The top-down channel of the configuration's features (people, faces, "
                   "objects)")
      ->capture_default_str();
  command
      ->add_option("--match-iou", args->link.match_iou,
                   "A track and a detection pair only at IoU >= this")
      ->capture_default_str()
      ->check(FiniteRange(0.0, 1.0));
  command
      ->add_option("--max-missed", args->link.max_missed,
                   "A track unmatched for more than this many frames in a row ends")
      ->capture_default_str()
      ->check(FiniteRange(0, 100000));
  command
      ->add_option("--velocity-frames", args->link.velocity_frames,
                   "A track's velocity is its mean displacement over this many matched frames; "
                   "0: no prediction")
      ->capture_default_str()
      ->check(FiniteRange(0, 1000));
  args->command_line = command_line;
  command->callback([args, action, sequence, images] {
    if (sequence->count() == 0 && images->count() == 0) {
      throw CLI::RequiredError("--sequence or --images");
    }
    *action = [args] { return TrackDetectionsCommand(*args); };
  });
}

ATTEND_COMMAND(65, "track-detections", AddTrackDetectionsCommand);

}  // namespace attend
