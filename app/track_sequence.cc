#include "app/track_sequence.h"

#include <filesystem>
#include <fstream>
#include <opencv2/imgproc.hpp>
#include <system_error>
#include <variant>

#include "app/home.h"
#include "config/param_block.h"
#include "io/ground_truth.h"
#include "io/image_file.h"
#include "io/tracking_files.h"
#include "pipeline/options_io.h"
#include "pipeline/overlay.h"
#include "util/error.h"
#include "util/json_text.h"
#include "util/output_folder.h"
#include "util/strings.h"

namespace attend {

namespace {

namespace fs = std::filesystem;

// Frames: a sequence folder (left view only) or a plain folder of images, at their native size
// (boxes are in the source's pixels, as the ground truth is).
std::unique_ptr<FrameSource> OpenTrackSource(const TrackRequest& request,
                                             SequenceOptions* options) {
  std::error_code error;
  const std::string& sequence = request.sequence;
  if (request.images.empty() && fs::is_directory(sequence, error) &&
      !fs::is_directory(fs::path(sequence) / "left", error) &&
      fs::is_directory(fs::path(sequence) / "img", error)) {
    throw InputError("folder " + sequence + ": no left/ folder, but an img/ folder (an OTB " +
                     "sequence?); track a plain folder of images with --images " +
                     (fs::path(sequence) / "img").string());
  }
  options->source.folder = request.images.empty() ? sequence : "";
  options->source.images = request.images;
  options->first_frame = request.first_frame;
  options->last_frame = request.last_frame;
  options->resize = "native";
  return OpenFrameSource(*options);
}

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
    const bool found = view.state == TrackState::kFound;
    if (!view.roi.empty()) cv::rectangle(overlay, view.roi, colour, 1, cv::LINE_4);
    cv::rectangle(overlay, view.box, colour, found ? 2 : 1, cv::LINE_8);
    DrawTargetLabel(&overlay, view.id, view.box,
                    found ? "" : std::string(" (") + TrackStateName(view.state) + ")", font_scale);
  }
  DrawCaption(&overlay, "frame " + std::to_string(index), font_scale);
  return overlay;
}

class MaskDump final : public TrackObserver {
 public:
  explicit MaskDump(std::string out) : out_(std::move(out)) {}
  void OnFrame(const StereoFrame& frame, const std::vector<TargetView>& views) override {
    const std::string stem = FrameStem(frame.index) + ".png";
    for (const TargetView& view : views) {
      const cv::Mat mask =
          view.mask.empty() ? cv::Mat(frame.left.size(), CV_8UC1, cv::Scalar(0)) : view.mask;
      WriteImageFile((out_ / "masks" / std::to_string(view.id) / stem).string(), mask);
    }
  }

 private:
  fs::path out_;
};

class OverlayDump final : public TrackObserver {
 public:
  explicit OverlayDump(std::string out) : out_(std::move(out)) {}
  void OnFrame(const StereoFrame& frame, const std::vector<TargetView>& views) override {
    WriteImageFile((out_ / "overlay" / (FrameStem(frame.index) + ".png")).string(),
                   DrawTrackOverlay(frame.left, frame.index, views));
  }

 private:
  fs::path out_;
};

// Targets start on the first frame of the range, one per box, ids 1, 2, ... in order. Every
// box must lie inside the frame (a usage error, like a box of zero size) before any starts.
void StartOnBoxes(const TrackRequest& request, const StereoFrame& frame, TargetTracker* tracker) {
  const std::vector<cv::Rect>& boxes = request.boxes;
  const cv::Rect image(0, 0, frame.left.cols, frame.left.rows);
  auto what = [&](size_t i) {
    return request.box_texts[i] + " (target " + std::to_string(i + 1) + ", frame " +
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
    const char* why = TrackerKindOf(request.options.kind).no_target;
    throw InputError(what(i) + ": " +
                     (why != nullptr
                          ? std::string(why)
                          : "the " + std::string(tracker->name()) + " tracker cannot start on it"));
  }
}

}  // namespace

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

TargetTrackerOptions ResolveTrackerOptions(const std::string& config,
                                           const std::vector<std::string>& sets,
                                           const std::string& command) {
  auto read = [&](ParamBlock root) {
    for (const std::string& assignment : sets) {
      if (assignment.rfind("tracker.", 0) != 0) {
        throw ConfigError("--set " + assignment + ": " + command +
                          " takes only tracker.KEY=VALUE, KEY one of " + Join(TrackerKeys(), ", "));
      }
      root.Override(assignment);
    }
    return ReadOptions(root).attention.tracker;
  };
  if (!config.empty()) return read(ParamBlock::LoadFile(config));
  // The kind (from --set, else the default) picks the file the others apply over.
  const TargetTrackerOptions given = read(ParamBlock::Parse("", "--set"));
  const std::string base = TrackConfigPath(given.kind);
  return base.empty() ? given : read(ParamBlock::LoadFile(base));
}

std::unique_ptr<TrackObserver> MakeMaskDump(const std::string& out) {
  return std::make_unique<MaskDump>(out);
}

std::unique_ptr<TrackObserver> MakeOverlayDump(const std::string& out) {
  return std::make_unique<OverlayDump>(out);
}

namespace {

// A frame's results as rows of tracks.csv and views for the observers (`views` replaced); the
// ids reported lost are appended to `lost`.
void RecordResults(int frame, const std::vector<TrackResult>& results, const TargetTracker& tracker,
                   std::vector<TrackRow>* rows, std::vector<TargetView>* views,
                   std::vector<int>* lost) {
  views->clear();
  for (const TrackResult& result : results) {
    rows->push_back({frame, result.id, cv::Rect2d(result.box), TrackStateName(result.state)});
    if (result.state == TrackState::kLost) lost->push_back(result.id);
    const cv::Mat mask = result.state == TrackState::kFound ? tracker.Mask(result.id) : cv::Mat();
    views->push_back({result.id, result.state, result.box, result.roi, mask});
  }
}

void WriteSummary(const std::string& path, const nlohmann::json& summary) {
  std::ofstream file(path);
  file << JsonText(summary, 2) << "\n";
  if (!file) throw OutputError(path + ": cannot write the summary");
}

}  // namespace

nlohmann::json TrackSequence(const TrackRequest& request,
                             const std::vector<TrackObserver*>& observers) {
  ATTEND_CHECK(request.box_texts.size() == request.boxes.size()) << "one text per box";
  const std::vector<cv::Rect>& boxes = request.boxes;
  SequenceOptions source_options;
  const std::unique_ptr<FrameSource> source = OpenTrackSource(request, &source_options);
  StereoFrame frame;
  if (!source->Next(&frame)) {
    throw InputError(source_options.source.Describe() + ": no frame in the range " +
                     request.range_text);
  }
  const int first_frame = frame.index;

  const std::unique_ptr<TargetTracker> tracker = TargetTracker::Create(request.options);
  StartOnBoxes(request, frame, tracker.get());

  const fs::path out(request.out);
  const FolderLock lock = PrepareOutputFolder(request.out, request.overwrite,
                      {"track output",
                       {"tracks.csv", "track.json", "masks", "overlay"},
                       [](const std::string& folder) {
                         std::error_code error;
                         return fs::is_regular_file(fs::path(folder) / "tracks.csv", error);
                       }});
  const std::string tracks_path = (out / "tracks.csv").string();
  const auto tell = [&](const std::vector<TargetView>& views) {
    for (TrackObserver* observer : observers) observer->OnFrame(frame, views);
  };

  std::vector<TrackRow> rows;
  std::vector<TargetView> views;
  for (const int id : tracker->ids()) {
    const cv::Mat mask = tracker->Mask(id).clone();
    const cv::Rect box = cv::boundingRect(mask);
    rows.push_back({frame.index, id, cv::Rect2d(box), "found"});
    views.push_back({id, TrackState::kFound, box, cv::Rect(), mask});
  }
  tell(views);

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
      RecordResults(frame.index, results, *tracker, &rows, &views, &lost);
      tell(views);
    }
  } catch (const InputError& e) {
    WriteTracksCsv(tracks_path, rows);
    throw InputError(std::string(e.what()) + " (" + tracks_path + " holds frames " +
                     std::to_string(first_frame) + ".." + std::to_string(last_frame) + ")");
  }
  WriteTracksCsv(tracks_path, rows);

  nlohmann::json summary = {{"source", source_options.source.Describe()},
                                  {"out", request.out},
                                  {"tracker", tracker->name()},
                                  {"first_frame", first_frame},
                                  {"last_frame", last_frame},
                                  {"frames", frames},
                                  {"targets", boxes.size()},
                                  {"lost", lost},
                                  {"ms_per_frame", frames > 1 ? track_ms / (frames - 1) : 0.0}};
  // The kind's own settings (the BIP's mode and occlusion rules).
  const TrackerKindInfo& kind = TrackerKindOf(request.options.kind);
  for (const TrackerSetting& setting : kind.settings(request.options)) {
    std::visit([&](const auto& value) { summary[setting.key] = value; }, setting.value);
  }
  // The same summary beside tracks.csv, so that the folder says which kind tracked.
  WriteSummary((out / "track.json").string(), summary);
  return summary;
}

}  // namespace attend
