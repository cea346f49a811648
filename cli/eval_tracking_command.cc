// attend eval-tracking: the OTB one-pass scores of a tracks.csv, as `attend track` writes it,
// against OTB ground truth or a sequence's gt/objects.csv (SPEC 3.2, 4; docs/TRACKING.md).
#include <iostream>
#include <memory>
#include <optional>
#include <string>

#include "app/score_tracks.h"
#include "cli/cli_options.h"
#include "cli/commands.h"
#include "util/json_text.h"

namespace attend {

namespace {

struct EvalTrackingArguments {
  std::string tracks;
  std::string gt;
  std::optional<int> id;
  std::optional<int> gt_id;
  std::string frames;
};

int EvalTracking(const EvalTrackingArguments& args) {
  ScoreTracksRequest request{args.tracks, args.gt, args.id, args.gt_id};
  if (!args.frames.empty()) {
    const FrameRange range = ParseFrameRange(args.frames);
    request.has_range = true;
    request.first_frame = range.first;
    request.last_frame = range.last;
  }
  std::cout << JsonText(ScoreTracks(request), 2) << std::endl;
  return 0;
}

}  // namespace

void AddEvalTrackingCommand(CLI::App& app, const std::string&, CommandAction* action) {
  auto args = std::make_shared<EvalTrackingArguments>();
  CLI::App* command = app.add_subcommand(
      "eval-tracking",
      "Score tracks.csv against ground truth with the OTB one-pass evaluation (Wu, Lim, Yang, "
      "CVPR 2013; docs/TRACKING.md): success AUC over IoU thresholds 0, 0.05, ..., 1 (success "
      "at t: IoU > t) and precision at 20 px (centre error <= 20). Each target is scored from its "
      "first frame to the last frame of the ground truth, over the frames that have a true box; "
      "a frame without a row for the target scores 0, and a target not found keeps its last "
      "known box. Prints one JSON object with the scores per target id.");
  command->add_option("TRACKS", args->tracks, "tracks.csv written by attend track")->required();
  command
      ->add_option("--gt", args->gt,
                   "Ground truth: an OTB groundtruth_rect.txt (line i + 1 is frame i, 1-based "
                   "pixels), or the gt/objects.csv of an `attend synth` sequence")
      ->required();
  command->add_option("--id", args->id, "Score only this target id (default: every target)");
  command->add_option("--gt-id", args->gt_id,
                      "The object of gt/objects.csv to score against (needed when it holds more "
                      "than one)");
  command->add_option("--frames", args->frames,
                      "Score only frames FIRST:LAST, inclusive (default: from each target's "
                      "first frame to the end of the ground truth)");
  command->callback([args, action] { *action = [args] { return EvalTracking(*args); }; });
}

ATTEND_COMMAND(60, "eval-tracking", AddEvalTrackingCommand);

}  // namespace attend
