// attend track: a tracker of the kind tracker.kind (tracker/target_tracker.h: the BIP template
// tracker, KCF or CSRT) over a sequence, started from boxes on its first frame (SPEC 3.2;
// docs/TRACKING.md). cli/eval_tracking_command.cc scores what it writes.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <set>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include "cli/cli_options.h"
#include "cli/commands.h"
#include "config/param_block.h"
#include "eval/tracking_scores.h"
#include "io/ground_truth.h"
#include "io/image_file.h"
#include "io/sequence.h"
#include "io/tracking_files.h"
#include "pipeline/options_io.h"
#include "pipeline/overlay.h"
#include "tracker/target_tracker.h"
#include "util/error.h"
#include "util/json_text.h"
#include "util/output_folder.h"
#include "util/strings.h"

namespace attend {

namespace {

namespace fs = std::filesystem;

const std::vector<std::string>& DumpKinds() {
  static const std::vector<std::string> kinds = {"masks", "overlay"};
  return kinds;
}

// The keys of the configuration's tracker block (pipeline/options_io.h binds them to
// TargetTrackerOptions), without the "tracker." prefix.
const std::vector<std::string>& TrackerKeys() {
  static const std::vector<std::string> keys = [] {
    std::vector<std::string> result;
    for (const std::string& key : ConfigurationKeys()) {
      if (key.rfind("tracker.", 0) == 0) result.push_back(key.substr(8));
    }
    return result;
  }();
  return keys;
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

// The `tracker.*` keys of --set over TargetTrackerOptions' defaults, read by the configuration's
// one binding (pipeline/options_io.h), so that keys, ranges and messages (a kind that does not
// exist, an option of another kind) are those of `attend run`.
TargetTrackerOptions ResolveTrackerOptions(const std::vector<std::string>& sets) {
  ParamBlock root = ParamBlock::Parse("", "--set");
  for (const std::string& assignment : sets) {
    if (assignment.rfind("tracker.", 0) != 0) {
      throw ConfigError("--set " + assignment +
                        ": attend track takes only tracker.KEY=VALUE, KEY one of " +
                        Join(TrackerKeys(), ", "));
    }
    root.Override(assignment);
  }
  return ReadOptions(root).attention.tracker;
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
// Frames: a sequence folder (left view only) or a plain folder of images, at their native size
// (boxes are in the source's pixels, as the ground truth is).

std::unique_ptr<FrameSource> OpenTrackSource(const std::string& sequence, const std::string& images,
                                             const FrameRange& range, SequenceOptions* options) {
  std::error_code error;
  if (images.empty() && fs::is_directory(sequence, error) &&
      !fs::is_directory(fs::path(sequence) / "left", error) &&
      fs::is_directory(fs::path(sequence) / "img", error)) {
    throw InputError("folder " + sequence + ": no left/ folder, but an img/ folder (an OTB " +
                     "sequence?); track a plain folder of images with --images " +
                     (fs::path(sequence) / "img").string());
  }
  options->folder = images.empty() ? sequence : "";
  options->images = images;
  options->first_frame = range.first;
  options->last_frame = range.last;
  options->resize = "native";
  return FrameSource::Open(*options);
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

// One target in one frame, as written and drawn.
struct TargetView {
  int id = 0;
  std::string state;
  cv::Rect box;
  cv::Rect roi;  // empty on the first frame
  cv::Mat mask;  // empty when not found
};

// The frame with each target's pixels tinted, its box (thick when found) and its ROI (thin), in
// the colour of its id.
cv::Mat DrawTrackOverlay(const cv::Mat& frame, int index, const std::vector<TargetView>& views) {
  cv::Mat overlay = frame.clone();
  for (const TargetView& view : views) {
    if (view.mask.empty()) continue;
    cv::Mat tinted(frame.size(), CV_8UC3, TargetColour(view.id));
    cv::addWeighted(frame, 0.55, tinted, 0.45, 0.0, tinted);
    tinted.copyTo(overlay, view.mask);
  }
  const double font_scale = OverlayFontScale(frame.cols);
  for (const TargetView& view : views) {
    const cv::Scalar colour = TargetColour(view.id);
    const bool found = view.state == "found";
    if (!view.roi.empty()) cv::rectangle(overlay, view.roi, colour, 1, cv::LINE_4);
    cv::rectangle(overlay, view.box, colour, found ? 2 : 1, cv::LINE_8);
    DrawTargetLabel(&overlay, view.id, view.box, found ? "" : " (" + view.state + ")", font_scale);
  }
  DrawCaption(&overlay, "frame " + std::to_string(index), font_scale);
  return overlay;
}

void WriteImage(const fs::path& path, const cv::Mat& image) {
  std::error_code error;
  fs::create_directories(path.parent_path(), error);
  bool written = false;
  try {
    written = !error && cv::imwrite(path.string(), image);
  } catch (const cv::Exception&) {
    written = false;
  }
  if (!written) throw OutputError(path.string() + ": cannot write the image");
}

void DumpFrame(const fs::path& out, const Dumps& dumps, const StereoFrame& frame,
               const std::vector<TargetView>& views) {
  const std::string stem = FrameStem(frame.index) + ".png";
  if (dumps.masks) {
    for (const TargetView& view : views) {
      const cv::Mat mask =
          view.mask.empty() ? cv::Mat(frame.left.size(), CV_8UC1, cv::Scalar(0)) : view.mask;
      WriteImage(out / "masks" / std::to_string(view.id) / stem, mask);
    }
  }
  if (dumps.overlay)
    WriteImage(out / "overlay" / stem, DrawTrackOverlay(frame.left, frame.index, views));
}

int Track(const TrackArguments& args) {
  // Everything on the command line is checked before any frame is read.
  const TargetTrackerOptions options = ResolveTrackerOptions(args.sets);
  const FrameRange range = args.frames.empty() ? FrameRange() : ParseFrameRange(args.frames);
  const Dumps dumps = ParseDumps(args.dump);
  std::vector<cv::Rect> boxes;
  for (const std::string& init : args.inits) boxes.push_back(ParseBox(init));

  SequenceOptions source_options;
  const std::unique_ptr<FrameSource> source =
      OpenTrackSource(args.sequence, args.images, range, &source_options);
  StereoFrame frame;
  if (!source->Next(&frame)) {
    throw InputError(source_options.Describe() + ": no frame in the range " +
                     (args.frames.empty() ? std::string("0:") : args.frames));
  }
  const int first_frame = frame.index;

  // Targets start on the first frame of the range, one per box, ids 1, 2, ... in order. Every
  // box must lie inside the frame (a usage error, like a box of zero size) before any starts.
  const std::unique_ptr<TargetTracker> tracker = TargetTracker::Create(options);
  const cv::Rect image(0, 0, frame.left.cols, frame.left.rows);
  auto what = [&](size_t i) {
    return "--init " + BoxText(boxes[i]) + " (target " + std::to_string(i + 1) + ", frame " +
           std::to_string(frame.index) + ", " + frame.left_path + ")";
  };
  for (size_t i = 0; i < boxes.size(); ++i) {
    if ((boxes[i] & image) == boxes[i]) continue;
    throw ConfigError(what(i) + ": the box " +
                      ((boxes[i] & image).empty() ? std::string("lies outside")
                                                  : std::string("does not lie inside")) +
                      " the " + std::to_string(image.width) + "x" + std::to_string(image.height) +
                      " frame (x in 0.." + std::to_string(image.width) + " - w, y in 0.." +
                      std::to_string(image.height) + " - h)");
  }
  for (size_t i = 0; i < boxes.size(); ++i) {
    const int id = tracker->StartFromBox(frame.left, boxes[i]);
    if (id >= 0) continue;
    if (options.kind != TrackerKind::kBip) {
      throw InputError(what(i) + ": the " + tracker->name() + " tracker cannot start on it");
    }
    throw InputError(what(i) +
                     ": no target: no region of the frame's over-segmentation lies mostly inside "
                     "the box, or the target is too thin for a template");
  }

  const fs::path out(args.out);
  PrepareOutputFolder(args.out, args.overwrite,
                      {"track output",
                       {"tracks.csv", "track.json", "masks", "overlay"},
                       [](const std::string& folder) {
                         std::error_code error;
                         return fs::is_regular_file(fs::path(folder) / "tracks.csv", error);
                       }});
  const std::string tracks_path = (out / "tracks.csv").string();

  std::vector<TrackRow> rows;
  std::vector<TargetView> views;
  for (const int id : tracker->ids()) {
    const cv::Mat mask = tracker->Mask(id).clone();
    const cv::Rect box = cv::boundingRect(mask);
    rows.push_back({frame.index, id, cv::Rect2d(box), "found"});
    views.push_back({id, "found", box, cv::Rect(), mask});
  }
  DumpFrame(out, dumps, frame, views);

  int frames = 1;
  int last_frame = frame.index;
  double track_ms = 0.0;
  std::vector<int> lost;
  std::vector<TrackResult> results;
  try {
    while (!tracker->ids().empty() && source->Next(&frame)) {
      results.clear();
      tracker->Track(frame.left, &results);
      track_ms += tracker->milliseconds();
      ++frames;
      last_frame = frame.index;
      views.clear();
      for (const TrackResult& result : results) {
        const std::string state = TrackStateName(result.state);
        rows.push_back({frame.index, result.id, cv::Rect2d(result.box), state});
        if (result.state == TrackState::kLost) lost.push_back(result.id);
        const cv::Mat mask =
            result.state == TrackState::kFound ? tracker->Mask(result.id) : cv::Mat();
        views.push_back({result.id, state, result.box, result.roi, mask});
      }
      DumpFrame(out, dumps, frame, views);
    }
  } catch (const InputError& e) {
    WriteTracksCsv(tracks_path, rows);
    throw InputError(std::string(e.what()) + " (" + tracks_path + " holds frames " +
                     std::to_string(first_frame) + ".." + std::to_string(last_frame) + ")");
  }
  WriteTracksCsv(tracks_path, rows);

  const nlohmann::json summary = {{"source", source_options.Describe()},
                                  {"out", args.out},
                                  {"tracker", tracker->name()},
                                  {"first_frame", first_frame},
                                  {"last_frame", last_frame},
                                  {"frames", frames},
                                  {"targets", boxes.size()},
                                  {"lost", lost},
                                  {"ms_per_frame", frames > 1 ? track_ms / (frames - 1) : 0.0}};
  // The same summary beside tracks.csv, so that the folder says which kind tracked.
  const std::string summary_path = (out / "track.json").string();
  std::ofstream summary_file(summary_path);
  summary_file << JsonText(summary, 2) << "\n";
  if (!summary_file) throw OutputError(summary_path + ": cannot write the summary");
  std::cout << JsonText(summary) << std::endl;
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

}  // namespace attend
