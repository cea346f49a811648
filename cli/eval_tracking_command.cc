// attend eval-tracking: the OTB one-pass scores of a tracks.csv, as `attend track` writes it,
// against OTB ground truth or a sequence's gt/objects.csv; or, with --otb, the OTB one-pass
// evaluation of several trackers over a folder of OTB sequences, with its HTML report
// (SPEC 3.2, 4; docs/TRACKING.md).
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/evaluate_otb.h"
#include "app/score_tracks.h"
#include "app/track_sequence.h"
#include "cli/cli_options.h"
#include "cli/commands.h"
#include "util/error.h"
#include "util/json_text.h"
#include "util/strings.h"

namespace attend {

namespace {

struct EvalTrackingArguments {
  // Scoring a tracks.csv.
  std::string tracks;
  std::string gt;
  std::optional<int> id;
  std::optional<int> gt_id;
  std::string frames;
  // The OTB evaluation (--otb).
  std::string otb;
  std::string out;
  std::string trackers;
  std::string sequences;
  std::string config;
  std::vector<std::string> sets;
  bool overwrite = false;
};

// The two modes take different flags; a flag of the other mode is a usage error.
void CheckMode(const EvalTrackingArguments& args, const CLI::App& command) {
  const char* usage =
      "give either TRACKS --gt GT (score a tracks.csv) or --otb DIR --out REPORT (the OTB "
      "evaluation of several trackers)";
  std::vector<std::string> score_flags, otb_flags;
  for (const char* flag : {"TRACKS", "--gt", "--id", "--gt-id", "--frames"}) {
    if (command.count(flag) > 0) score_flags.push_back(flag);
  }
  for (const char* flag :
       {"--otb", "--out", "--trackers", "--sequences", "--config", "--set", "--overwrite"}) {
    if (command.count(flag) > 0) otb_flags.push_back(flag);
  }
  if (!score_flags.empty() && !otb_flags.empty()) {
    throw ConfigError(Join(score_flags, ", ") + " and " + Join(otb_flags, ", ") +
                      ": the two modes do not mix; " + usage);
  }
  if (!otb_flags.empty()) {
    if (args.otb.empty()) throw ConfigError(Join(otb_flags, ", ") + " without --otb DIR; " + usage);
    if (args.out.empty()) throw ConfigError("--otb " + args.otb + ": --out REPORT is required");
    return;
  }
  if (args.tracks.empty() || args.gt.empty()) throw ConfigError(usage);
}

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

std::vector<std::string> ListArgument(const std::string& text) {
  std::vector<std::string> items;
  for (const std::string& item : Split(text, ',')) {
    if (!item.empty()) items.push_back(item);
  }
  return items;
}

int EvalOtb(const EvalTrackingArguments& args, const std::string& command_line) {
  OtbEvaluationRequest request;
  request.dir = args.otb;
  request.out = args.out;
  if (!args.trackers.empty()) request.trackers = ListArgument(args.trackers);
  request.sequences = ListArgument(args.sequences);
  request.attend = ResolveTrackerOptions(args.config, args.sets, "attend eval-tracking --otb");
  request.overwrite = args.overwrite;
  request.command_line = command_line;
  OtbObserver observer;
  observer.on_sequence = [](const OtbSequence& sequence, int index, int count) {
    std::cerr << "[otb] " << index + 1 << "/" << count << " " << sequence.name << ": "
              << sequence.images.size() << " frames" << std::endl;
  };
  observer.on_result = [](const OtbSequenceResult& result,
                          const std::vector<OtbTracker>& trackers) {
    std::string aucs;
    for (size_t t = 0; t < trackers.size(); ++t) {
      aucs += " " + trackers[t].name + " " + Fixed(result.runs[t].scores.success_auc, 3);
    }
    std::cerr << "[otb]   " << result.name << " AUC:" << aucs << std::endl;
  };
  const OtbResults results = EvaluateOtb(request, observer);
  std::cout << OtbSummaryText(results) << "report: " << args.out << "/index.html" << std::endl;
  return 0;
}

}  // namespace

void AddEvalTrackingCommand(CLI::App& app, const std::string& command_line, CommandAction* action) {
  auto args = std::make_shared<EvalTrackingArguments>();
  CLI::App* command = app.add_subcommand(
      "eval-tracking",
      "Score tracks.csv against ground truth with the OTB one-pass evaluation (Wu, Lim, Yang, "
      "CVPR 2013; docs/TRACKING.md): success AUC over IoU thresholds 0, 0.05, ..., 1 (success "
      "at t: IoU > t) and precision at 20 px (centre error <= 20). Each target is scored from its "
      "first frame to the last frame of the ground truth, over the frames that have a true box; "
      "a frame without a row for the target scores 0, and a target not found keeps its last "
      "known box. Prints one JSON object with the scores per target id.\n"
      "With --otb DIR --out REPORT instead: the OTB one-pass evaluation of several trackers "
      "over the OTB sequences in DIR (img/ and groundtruth_rect*.txt; DIR may be one "
      "sequence). Every tracker starts on frame 0 from the true box and runs to the end, the "
      "trackers taking turns frame by frame on one OpenCV thread, only their Track() calls "
      "timed. Writes REPORT/index.html (success and precision plots of all sequences and of "
      "each attribute, scores and ms per frame per sequence), REPORT/results.json and "
      "REPORT/tracks/<tracker>/<sequence>.csv, and prints a summary table.");
  command->add_option("TRACKS", args->tracks, "tracks.csv written by attend track");
  command->add_option("--gt", args->gt,
                      "Ground truth: an OTB groundtruth_rect.txt (line i + 1 is frame i, 1-based "
                      "pixels), or the gt/objects.csv of an `attend synth` sequence");
  command->add_option("--id", args->id, "Score only this target id (default: every target)");
  command->add_option("--gt-id", args->gt_id,
                      "The object of gt/objects.csv to score against (needed when it holds more "
                      "than one)");
  command->add_option("--frames", args->frames,
                      "Score only frames FIRST:LAST, inclusive (default: from each target's "
                      "first frame to the end of the ground truth)");
  command->add_option("--otb", args->otb,
                      "The OTB evaluation: a folder of OTB sequences (or one sequence)");
  command->add_option("--out", args->out, "--otb: the report folder, created if missing");
  command->add_option("--trackers", args->trackers,
                      "--otb: the trackers, comma-separated, from " +
                          Join(OtbTrackerNames(), ", ") +
                          " (default: all; attend is the tracker attend track builds)");
  command->add_option("--sequences", args->sequences,
                      "--otb: only these sequences, comma-separated, by name (Jogging-1) or "
                      "folder (Jogging: all its ground truths)");
  command->add_option("--config", args->config,
                      "--otb: the attend tracker's configuration (its tracker section; default: "
                      "configs/track.yaml, as attend track)");
  AddSetOption(command, &args->sets,
               "--otb: set an option of the attend tracker, --set tracker.KEY=VALUE with KEY one "
               "of " +
                   Join(TrackerKeys(), ", ") + " (repeatable)");
  command->add_flag("--overwrite", args->overwrite, "--otb: replace a previous report in REPORT");
  command->callback([args, action, command, command_line] {
    *action = [args, command, command_line] {
      CheckMode(*args, *command);
      return args->otb.empty() ? EvalTracking(*args) : EvalOtb(*args, command_line);
    };
  });
}

ATTEND_COMMAND(60, "eval-tracking", AddEvalTrackingCommand);

}  // namespace attend
