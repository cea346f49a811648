#include "app/evaluate_otb.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <opencv2/core/version.hpp>
#include <opencv2/imgproc.hpp>
#include <set>
#include <system_error>
#include <variant>

#include "eval/otb_report.h"
#include "io/frame_files.h"
#include "io/tracking_files.h"
#include "pyramid/bip.h"
#include "util/error.h"
#include "util/execution_context.h"
#include "util/json_text.h"
#include "util/output_folder.h"
#include "util/strings.h"
#include "util/timer.h"

namespace attend {

namespace {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

// Above any sequence's length, the largest tracker.lost_frames allows: an OpenCV tracker that
// fails keeps its last box to the end instead of ending the run.
constexpr int kNeverLost = 1000000;

// The processor's model name from /proc/cpuinfo, "unknown" when it does not say.
std::string CpuName() {
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::string line;
  while (std::getline(cpuinfo, line)) {
    if (line.rfind("model name", 0) != 0) continue;
    const size_t colon = line.find(':');
    if (colon != std::string::npos) return line.substr(line.find_first_not_of(" \t", colon + 1));
  }
  return "unknown";
}

// A value of the configuration's text (DescribeFields) as JSON: a number, a bool or a name.
Json ConfigValue(const FieldDescription& field) {
  const std::string& text = field.fallback;
  if (field.type == "bool") return text == "true";
  if (field.type == "int" || field.type == "number") {
    const double value = std::stod(text);
    if (field.type == "int") return static_cast<long long>(value);
    return value;
  }
  if (text.size() >= 2 && text.front() == '"' && text.back() == '"') {
    return text.substr(1, text.size() - 2);
  }
  return text;
}

// The keys of the tracker section that `options`' kind reads, with their values, as the
// configuration spells them.
Json TrackerOptionsJson(const TargetTrackerOptions& options) {
  Json json = {{"kind", TrackerKindName(options.kind)}};
  const TrackerKindInfo& kind = TrackerKindOf(options.kind);
  ForEachTrackerOptionBlock([&](auto block, const auto& fields) {
    for (const FieldDescription& field : DescribeFields(fields, options.*block)) {
      if (HasKey(fields, field.key) && kind.uses_key(field.key)) {
        json[field.key] = ConfigValue(field);
      }
    }
  });
  return json;
}

// "bip, mode bounded, occlusion on": the kind and the settings attend track reports.
std::string DescribeTracker(const std::string& name, const TargetTrackerOptions& options) {
  std::string text = TrackerKindName(options.kind);
  if (name != "attend") {
    return text + ", OpenCV's defaults" +
           (options.kind == TrackerKind::kKcf ? std::string(" but detect_thresh 0") : "");
  }
  for (const TrackerSetting& setting : TrackerKindOf(options.kind).settings(options)) {
    text += ", " + setting.key + " ";
    std::visit(
        [&](const auto& value) {
          if constexpr (std::is_same_v<std::decay_t<decltype(value)>, bool>) {
            text += value ? "on" : "off";
          } else {
            text += value;
          }
        },
        setting.value);
  }
  return text;
}

void CheckTrackerNames(const std::vector<std::string>& names) {
  const std::string flag = "--trackers " + Join(names, ",");
  if (names.empty()) {
    throw ConfigError("--trackers: no tracker; choose from " + Join(OtbTrackerNames(), ", "));
  }
  std::set<std::string> seen;
  for (const std::string& name : names) {
    const std::vector<std::string>& known = OtbTrackerNames();
    if (std::find(known.begin(), known.end(), name) == known.end()) {
      throw ConfigError(flag + ": unknown tracker '" + name + "'" + DidYouMean(name, known) +
                        "; choose from " + Join(known, ", "));
    }
    if (!seen.insert(name).second) throw ConfigError(flag + ": '" + name + "' is named twice");
  }
}

// The sequences named in `names` (a sequence's name or its folder's), in the order found.
std::vector<OtbSequence> SelectSequences(const std::vector<OtbSequence>& found,
                                         const std::vector<std::string>& names) {
  if (names.empty()) return found;
  const auto named = [&names](const OtbSequence& sequence) {
    return std::find(names.begin(), names.end(), sequence.name) != names.end() ||
           std::find(names.begin(), names.end(), sequence.folder_name) != names.end();
  };
  std::vector<std::string> available;
  for (const OtbSequence& sequence : found) available.push_back(sequence.name);
  for (const std::string& name : names) {
    const bool known = std::any_of(found.begin(), found.end(), [&](const OtbSequence& s) {
      return s.name == name || s.folder_name == name;
    });
    if (!known) {
      throw ConfigError("--sequences " + Join(names, ",") + ": no sequence '" + name + "'" +
                        DidYouMean(name, available) + " (found: " + Join(available, ", ") + ")");
    }
  }
  std::vector<OtbSequence> chosen;
  for (const OtbSequence& sequence : found) {
    if (named(sequence)) chosen.push_back(sequence);
  }
  return chosen;
}

cv::Rect RoundedBox(const cv::Rect2d& box) {
  const int x0 = static_cast<int>(std::lround(box.x)), y0 = static_cast<int>(std::lround(box.y));
  const int x1 = static_cast<int>(std::lround(box.x + box.width));
  const int y1 = static_cast<int>(std::lround(box.y + box.height));
  return {x0, y0, x1 - x0, y1 - y0};
}

// Frame `f` of a sequence as 8-bit BGR; InputError naming the sequence, frame and file.
cv::Mat ReadSequenceFrame(const OtbSequence& sequence, int f, const cv::Size& size) {
  cv::Mat frame;
  try {
    frame = ReadFrameFile(sequence.first_image + f, sequence.images[f]);
  } catch (const InputError& e) {
    throw InputError(sequence.name + ": " + e.what());
  }
  if (!size.empty() && frame.size() != size) {
    throw InputError(sequence.name + ": frame " + std::to_string(sequence.first_image + f) + " (" +
                     sequence.images[f] + ") is " + std::to_string(frame.cols) + "x" +
                     std::to_string(frame.rows) + ", the first frame " +
                     std::to_string(size.width) + "x" + std::to_string(size.height));
  }
  return frame;
}

// One tracker following the sequence's target, with what it answered frame by frame.
struct Follower {
  std::unique_ptr<TargetTracker> tracker;
  bool active = false;
  double total_ms = 0.0;
  std::vector<TrackRow> rows;        // its tracks.csv
  std::vector<cv::Rect2d> boxes;     // its answer per frame (empty: none)
  std::vector<TrackResult> results;  // the last Track() call's
  OtbRun run;
};

// Starts the follower on frame 0 from the true box (clipped to the frame). Its first answer is
// the box of the target it started (as attend track's first row).
void StartFollower(Follower* follower, const cv::Mat& frame, const cv::Rect& box, int frames) {
  follower->boxes.assign(frames, cv::Rect2d());
  const cv::Rect inside = box & cv::Rect(0, 0, frame.cols, frame.rows);
  const int id = inside.empty() ? -1 : follower->tracker->StartFromBox(frame, inside);
  if (id < 0) return;
  follower->active = true;
  follower->run.started = true;
  follower->boxes[0] = cv::Rect2d(cv::boundingRect(follower->tracker->Mask(id)));
  follower->rows.push_back({0, 1, follower->boxes[0], "found"});
}

// One timed Track() call on frame `f`; a target no longer tracked keeps its last box.
void FollowFrame(Follower* follower, const cv::Mat& frame, int f) {
  OtbRun& run = follower->run;
  if (!run.started) return;
  if (!follower->active) {
    follower->boxes[f] = follower->boxes[f - 1];
    follower->rows.push_back({f, 1, follower->boxes[f], "lost"});
    ++run.lost_frames;
    return;
  }
  follower->results.clear();
  const Stopwatch watch;
  follower->tracker->Track(frame, &follower->results);
  follower->total_ms += watch.ElapsedMs();
  ++run.updates;
  const bool gone = follower->results.empty();  // removed without a report: lost
  const TrackState state = gone ? TrackState::kLost : follower->results[0].state;
  follower->boxes[f] = gone ? follower->boxes[f - 1] : cv::Rect2d(follower->results[0].box);
  follower->rows.push_back({f, 1, follower->boxes[f], TrackStateName(state)});
  if (state == TrackState::kOccluded) ++run.not_found;
  if (state == TrackState::kLost) {
    follower->active = false;
    ++run.lost_frames;
  }
}

// Tracks one sequence with every tracker, the trackers taking turns frame by frame (the first
// one rotating, so that load from elsewhere falls on all of them alike); writes their tracks.
OtbSequenceResult TrackOtbSequence(const OtbSequence& sequence,
                                   const std::vector<TargetTrackerOptions>& options,
                                   const std::vector<std::string>& names, const fs::path& out,
                                   BipPool* pool, std::vector<std::string>* notes) {
  const int frames = static_cast<int>(sequence.images.size());
  const int count = static_cast<int>(options.size());
  const cv::Mat first = ReadSequenceFrame(sequence, 0, cv::Size());
  std::vector<Follower> followers(count);
  for (int t = 0; t < count; ++t) {
    followers[t].tracker = TargetTracker::Create(options[t], pool);
    StartFollower(&followers[t], first, RoundedBox(sequence.truth[0]), frames);
    if (!followers[t].run.started) {
      notes->push_back(sequence.name + ": " + names[t] + " could not start on the first box " +
                       "(it scores 0 on this sequence)");
    }
  }
  for (int f = 1; f < frames; ++f) {
    const cv::Mat frame = ReadSequenceFrame(sequence, f, first.size());
    for (int k = 0; k < count; ++k) FollowFrame(&followers[(f + k) % count], frame, f);
  }
  OtbSequenceResult result;
  result.name = sequence.name;
  result.folder = sequence.folder;
  result.ground_truth = sequence.ground_truth;
  result.frames = frames;
  result.width = first.cols;
  result.height = first.rows;
  result.attributes = sequence.attributes;
  for (int t = 0; t < count; ++t) {
    Follower& follower = followers[t];
    OtbRun& run = follower.run;
    run.scores = ScoreTracking(follower.boxes, sequence.truth);
    run.ms_per_frame = run.updates > 0 ? follower.total_ms / run.updates : 0.0;
    run.tracks = "tracks/" + names[t] + "/" + sequence.name + ".csv";
    std::error_code error;
    fs::create_directories(out / "tracks" / names[t], error);
    if (error) {
      throw OutputError((out / "tracks" / names[t]).string() + ": cannot create the folder (" +
                        error.message() + ")");
    }
    WriteTracksCsv((out / run.tracks).string(), follower.rows);
    result.runs.push_back(run);
  }
  return result;
}

FolderLock PrepareReportFolder(const OtbEvaluationRequest& request) {
  return PrepareOutputFolder(
      request.out, request.overwrite,
      {"OTB report", {"index.html", "results.json", "tracks"}, [](const std::string& folder) {
         std::error_code error;
         return fs::is_regular_file(fs::path(folder) / "results.json", error) ||
                fs::is_directory(fs::path(folder) / "tracks", error);
       }});
}

}  // namespace

const std::vector<std::string>& OtbTrackerNames() {
  static const std::vector<std::string> names = {"attend", "kcf", "csrt"};
  return names;
}

TargetTrackerOptions OtbTrackerOptions(const std::string& name,
                                       const TargetTrackerOptions& attend) {
  if (name == "attend") return attend;
  TargetTrackerOptions options;
  ATTEND_CHECK(name == "kcf" || name == "csrt") << "unknown tracker " << name;
  options.kind = name == "kcf" ? TrackerKind::kKcf : TrackerKind::kCsrt;
  options.opencv.lost_frames = kNeverLost;
  options.opencv.kcf_detect_thresh = 0.f;
  return options;
}

OtbResults EvaluateOtb(const OtbEvaluationRequest& request, const OtbObserver& observer) {
  CheckTrackerNames(request.trackers);
  OtbResults results;
  std::vector<TargetTrackerOptions> options;
  for (const std::string& name : request.trackers) {
    options.push_back(OtbTrackerOptions(name, request.attend));
    const std::string error = options.back().Check();
    if (!error.empty()) throw ConfigError(name + ": tracker." + error);
    results.trackers.push_back(
        {name, DescribeTracker(name, options.back()), TrackerOptionsJson(options.back())});
  }
  const std::vector<OtbSequence> sequences =
      SelectSequences(FindOtbSequences(request.dir, &results.notes), request.sequences);
  for (const OtbSequence& sequence : sequences) {
    results.notes.insert(results.notes.end(), sequence.notes.begin(), sequence.notes.end());
  }
  const FolderLock lock = PrepareReportFolder(request);
  results.dir = request.dir;
  results.command_line = request.command_line;
  results.date = UtcTimestamp();
  results.cpu = CpuName();
  results.opencv = CV_VERSION;

  // One OpenCV thread, as the benchmark: the trackers' times are comparable on a shared machine.
  ExecutionContext context(1);
  const ScopedOpenCvThreads threads(context);
  results.opencv_threads = context.threads();
  const fs::path out(request.out);
  const Stopwatch wall;
  for (size_t s = 0; s < sequences.size(); ++s) {
    if (observer.on_sequence) {
      observer.on_sequence(sequences[s], static_cast<int>(s), static_cast<int>(sequences.size()));
    }
    results.sequences.push_back(TrackOtbSequence(sequences[s], options, request.trackers, out,
                                                 context.Shared<BipPool>(), &results.notes));
    if (observer.on_result) observer.on_result(results.sequences.back(), results.trackers);
  }
  results.seconds = wall.ElapsedMs() / 1000.0;
  // The page, then results.json: a folder without results.json is not a finished report.
  ReplaceFileText((out / "index.html").string(), OtbReportHtml(results), "the OTB report page");
  ReplaceFileText((out / "results.json").string(), JsonText(OtbResultsJson(results), 2) + "\n",
                  "the OTB results");
  return results;
}

}  // namespace attend
