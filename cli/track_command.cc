// attend track: a tracker of the kind tracker.kind (tracker/target_tracker.h: the BIP template
// tracker, KCF or CSRT) over a sequence, started from boxes on its first frame (SPEC 3.2;
// docs/TRACKING.md). cli/eval_tracking_command.cc scores what it writes.
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "app/track_sequence.h"
#include "cli/cli_options.h"
#include "cli/commands.h"
#include "util/error.h"
#include "util/json_text.h"
#include "util/strings.h"

namespace attend {

namespace {

const std::vector<std::string>& DumpKinds() {
  static const std::vector<std::string> kinds = {"masks", "overlay"};
  return kinds;
}

std::string BoxText(const cv::Rect& box) {
  return std::to_string(box.x) + "," + std::to_string(box.y) + "," + std::to_string(box.width) +
         "," + std::to_string(box.height);
}

// "x,y,w,h": four integers, 0-based pixels of the first frame, w and h > 0.
cv::Rect ParseBox(const std::string& text) {
  const std::vector<std::string> fields = Split(text, ',');
  int value[4] = {0, 0, 0, 0};
  bool ok = fields.size() == 4;
  for (size_t i = 0; ok && i < 4; ++i) {
    try {
      size_t used = 0;
      value[i] = std::stoi(fields[i], &used);
      ok = used == fields[i].size() && !fields[i].empty();
    } catch (const std::exception&) {
      ok = false;
    }
  }
  if (!ok) {
    throw ConfigError("--init " + text +
                      ": expected x,y,w,h (four integers: the box's top-left corner and size in "
                      "0-based pixels of the first frame)");
  }
  if (value[2] <= 0 || value[3] <= 0) {
    throw ConfigError("--init " + text + ": the box's width and height must be > 0");
  }
  return {value[0], value[1], value[2], value[3]};
}

struct Dumps {
  bool masks = false;
  bool overlay = false;
};

Dumps ParseDumps(const std::string& text) {
  Dumps dumps;
  if (text.empty()) return dumps;
  for (const std::string& kind : Split(text, ',')) {
    if (kind == "masks") {
      dumps.masks = true;
    } else if (kind == "overlay") {
      dumps.overlay = true;
    } else {
      throw ConfigError("--dump " + text + ": unknown output '" + kind + "'" +
                        DidYouMean(kind, DumpKinds()) + "; choose from " + Join(DumpKinds(), ", "));
    }
  }
  return dumps;
}

// ---------------------------------------------------------------------------------------------
// attend track

struct TrackArguments {
  std::string sequence;
  std::string images;
  std::vector<std::string> inits;
  std::string out;
  std::vector<std::string> sets;
  std::string frames;
  std::string dump;
  bool overwrite = false;
};

int Track(const TrackArguments& args) {
  // Everything on the command line is checked before any frame is read.
  TrackRequest request;
  request.options = ResolveTrackerOptions("", args.sets, "attend track");
  const FrameRange range = args.frames.empty() ? FrameRange() : ParseFrameRange(args.frames);
  request.first_frame = range.first;
  request.last_frame = range.last;
  request.range_text = args.frames.empty() ? std::string("0:") : args.frames;
  const Dumps dumps = ParseDumps(args.dump);
  for (const std::string& init : args.inits) {
    request.boxes.push_back(ParseBox(init));
    request.box_texts.push_back("--init " + BoxText(request.boxes.back()));
  }
  request.sequence = args.sequence;
  request.images = args.images;
  request.out = args.out;
  request.overwrite = args.overwrite;

  std::vector<std::unique_ptr<TrackObserver>> dumpers;
  if (dumps.masks) dumpers.push_back(MakeMaskDump(args.out));
  if (dumps.overlay) dumpers.push_back(MakeOverlayDump(args.out));
  std::vector<TrackObserver*> observers;
  for (const auto& dumper : dumpers) observers.push_back(dumper.get());
  std::cout << JsonText(TrackSequence(request, observers)) << std::endl;
  return 0;
}

}  // namespace

void AddTrackCommand(CLI::App& app, const std::string&, CommandAction* action) {
  auto args = std::make_shared<TrackArguments>();
  CLI::App* command = app.add_subcommand(
      "track",
      "Track objects with the tracker of kind tracker.kind: bip, the BIP template tracker "
      "(thesis chapter 4, the default), or OpenCV's kcf or csrt (docs/TRACKING.md). Targets start "
      "on the first frame of the range, one per --init box (ids 1, 2, ... in "
      "order), and are tracked over the following frames at the source's native size. Writes "
      "OUT/tracks.csv (frame,id,x,y,w,h,state; one row per target per frame, the box the last "
      "known one when the state is occluded or lost) and OUT/track.json, a summary (the tracker "
      "kind, frames, lost targets, ms_per_frame: the mean time of the tracker's Track), which it "
      "also prints on one line. A lost target has no further rows; "
      "the command stops when every target is lost.");
  CLI::Option* sequence = command->add_option(
      "--sequence", args->sequence,
      "Sequence folder (SPEC 3.1): frames in SEQ/left (a right/ view is ignored)");
  CLI::Option* images = command->add_option(
      "--images", args->images,
      "A plain folder of images, frames in sorted file-name order (an OTB sequence's img/)");
  sequence->excludes(images);
  command
      ->add_option("--init", args->inits,
                   "A target's box x,y,w,h in 0-based pixels of the first frame, inside it "
                   "(repeatable)")
      ->type_name("X,Y,W,H")
      ->expected(1)
      ->allow_extra_args(false)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
      ->required();
  command->add_option("--out", args->out, "Output folder, created if missing")->required();
  AddSetOption(command, &args->sets,
               "Set a tracker option, the value parsed as YAML: --set tracker.KEY=VALUE with "
               "KEY one of " +
                   Join(TrackerKeys(), ", ") +
                   " (configs/README.md, tracker/tracker.h; repeatable)");
  command->add_option(
      "--frames", args->frames,
      "Frame range FIRST:LAST, inclusive (10:50, 10:, :99); targets start on FIRST");
  command->add_option("--dump", args->dump,
                      "Also write masks (OUT/masks/<id>/NNNNNN.png, 255 on the target's pixels) "
                      "and/or overlay (OUT/overlay/NNNNNN.png): --dump masks,overlay");
  command->add_flag("--overwrite", args->overwrite,
                    "Replace a previous track output (tracks.csv, masks/, overlay/) in OUT");
  command->callback([args, action, sequence, images] {
    if (sequence->count() == 0 && images->count() == 0) {
      throw CLI::RequiredError("--sequence or --images");
    }
    *action = [args] { return Track(*args); };
  });
}

ATTEND_COMMAND(50, "track", AddTrackCommand);

}  // namespace attend
