// Benchmark (SPEC 5): the BIP template tracker (tracker/tracker.h) in both modes against OpenCV's
// CSRT, KCF and CamShift on the same sequences, in the same run, on one thread, with the OTB
// one-pass scores of eval/tracking_scores.h; and the cost of tracking 1, 3 and 8 targets at once
// (thesis table 4.3). Prints a markdown report; docs/TRACKING.md holds one with its command.
//
//   tracking_bench [--data DIR] [--home DIR] [--repeat N] [--markdown FILE] [--sequences LIST]
//
// --sequences: a comma-separated subset of occlusions, lab, Couple, Crossing, Dog1, Jogging,
// otb (the four OTB sequences) and crowd (the several-targets cost); default: all.
//
// Sequences:
//  - sequences/occlusions.yaml and sequences/lab.yaml rendered in memory, left view: one
//    single-target sequence per chosen homogeneous object (kObjects), started on the first
//    frame in which the object is at least 95 % visible, from its ground-truth box there;
//  - OTB Couple, Crossing, Dog1 and Jogging (its first jogger, groundtruth_rect.1.txt) under
//    DIR/otb (skipped with a message when absent), started on frame 0 from the ground truth.
// Every method runs on every frame of a sequence; the methods take turns frame by frame (the
// first one rotates), so that load from other processes falls on all of them alike. What is
// timed is the update call on the 8-bit BGR frame and nothing else (no I/O, no scoring):
//   BIP:      TargetTracker::Track of kind bip (MultiTracker::Track, its colour conversion
//             included), once with tracker.mode thesis and once with bounded;
//   CSRT:     TargetTracker::Track of kind csrt (cv::TrackerCSRT::update, default Params);
//   KCF:      TargetTracker::Track of kind kcf (cv::TrackerKCF::update, default Params but
//             kcf_detect_thresh 0: always reports a box);
//             the OpenCV kinds run with lost_frames above any sequence's length, so that a
//             failure keeps the last box for good (the OTB rule below) and never ends the run;
//   CamShift: BGR -> HSV, the saturation/value mask, the hue back-projection of the histogram
//             taken in the initial box, and cv::CamShift (as OpenCV's samples/cpp/camshiftdemo).
// A method that reports failure keeps its last box (the OTB toolkit's rule; the BIP tracker
// reports its last known box while the target is occluded); a BIP target that is lost reports
// nothing afterwards and scores 0 in every later frame with ground truth. The first frame is
// scored with the box each method starts from (the BIP tracker's: its initial target's bounding
// box). ms/frame is the median over N repetitions of the mean update time over the updates made
// (a lost BIP target is not updated, so the frames after its loss cost it nothing and are not
// counted). "box > 4x truth": frames with a true box in which the method's box has more than four
// times the true box's area (a tracker that has grown over the background).

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <opencv2/core.hpp>
#include <opencv2/core/utility.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/tracking.hpp>
#include <opencv2/video/tracking.hpp>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "bench/bench_common.h"
#include "synth/renderer.h"
#include "synth/scene.h"
#include "eval/tracking_scores.h"
#include "io/tracking_files.h"
#include "tracker/target_tracker.h"
#include "tracker/tracker.h"
#include "util/timer.h"

namespace {

namespace fs = std::filesystem;

// The homogeneous objects tracked in each scene (skin, the textured shirt and the occluders that
// are never hidden are left out). occlusions.yaml: red box (hidden twice by the blue board), red
// ball (behind a red panel), green box (behind a green ellipse), orange ellipse (leaves the
// image and returns). lab.yaml: red box (the blue ball rolls over it), blue ball, green
// triangle, yellow box (enters at frame 30), purple box (approaches, 18 to 45 px).
struct SceneChoice {
  const char* file;
  std::vector<int> objects;
};
const SceneChoice kScenes[] = {{"occlusions.yaml", {1, 4, 5, 7}}, {"lab.yaml", {1, 2, 3, 4, 5}}};
// The crowd scene's objects that are not skin and are present at frame 0: the multi-target cost.
const std::vector<int> kCrowdObjects = {1, 2, 3, 4, 5, 6, 7, 9};
constexpr double kStartVisible = 0.95;

// CamShift as in samples/cpp/camshiftdemo.cpp.
constexpr int kHueBins = 16;
constexpr int kMinSaturation = 30;
constexpr int kMinValue = 10;

using Options = attend::bench::BenchOptions;
using attend::bench::CpuModel;
using attend::bench::Fixed;
using attend::bench::Median;
using attend::bench::UtcNow;

// ---------------------------------------------------------------------------------------------
// Sequences

struct Frames {
  std::string name;    // "occlusions", "OTB Couple"
  std::string source;  // for the report
  std::vector<cv::Mat> images;
};

// One target to follow through a sequence.
struct Task {
  const Frames* frames = nullptr;
  std::string object;             // "red_box (1)"
  std::string group;              // "synthetic occlusions", "synthetic lab", "OTB"
  int first = 0;                  // the frame the trackers start on
  cv::Rect init;                  // the start box
  std::vector<cv::Rect2d> truth;  // per frame; empty where there is none or before `first`
  int hidden = 0;                 // frames after `first` without a true box
};

cv::Rect Rounded(const cv::Rect2d& box) {
  const int x0 = static_cast<int>(std::lround(box.x)), y0 = static_cast<int>(std::lround(box.y));
  const int x1 = static_cast<int>(std::lround(box.x + box.width));
  const int y1 = static_cast<int>(std::lround(box.y + box.height));
  return {x0, y0, x1 - x0, y1 - y0};
}

void CountHidden(Task* task) {
  for (int f = task->first + 1; f < static_cast<int>(task->truth.size()); ++f) {
    if (task->truth[f].empty()) ++task->hidden;
  }
}

// Renders a scene's left views and the per-object ground truth.
void AddScene(const std::string& path, const std::vector<int>& object_ids,
              std::vector<std::unique_ptr<Frames>>* all, std::vector<Task>* tasks) {
  const attend::Scene scene = attend::LoadScene(path);
  const attend::SceneRenderer renderer(scene);
  auto frames = std::make_unique<Frames>();
  frames->name = scene.name;
  frames->source = "sequences/" + fs::path(path).filename().string();
  std::map<int, std::vector<attend::GtObject>> by_object;
  for (int f = 0; f < scene.frames; ++f) {
    attend::RenderedFrame rendered = renderer.Render(f);
    frames->images.push_back(rendered.left);
    for (const attend::GtObject& object : rendered.objects) by_object[object.id].push_back(object);
  }
  for (const int id : object_ids) {
    std::string name = "object " + std::to_string(id);
    for (const attend::SceneObject& object : scene.objects) {
      if (object.id == id) name = object.name + " (" + std::to_string(id) + ")";
    }
    Task task;
    task.frames = frames.get();
    task.object = name;
    task.group = "synthetic " + scene.name;
    task.truth.assign(scene.frames, cv::Rect2d());
    task.first = -1;
    for (const attend::GtObject& object : by_object[id]) {
      task.truth[object.frame] = object.box;
      if (task.first < 0 && object.visible_fraction >= kStartVisible) task.first = object.frame;
    }
    if (task.first < 0) {
      std::cerr << "tracking_bench: skipping " << name << " of " << path
                << ": never 95 % visible\n";
      continue;
    }
    for (int f = 0; f < task.first; ++f) task.truth[f] = cv::Rect2d();
    task.init = Rounded(task.truth[task.first]);
    CountHidden(&task);
    tasks->push_back(task);
  }
  all->push_back(std::move(frames));
}

void AddOtb(const fs::path& root, const std::string& name, const std::string& truth_file,
            std::vector<std::unique_ptr<Frames>>* all, std::vector<Task>* tasks) {
  const fs::path folder = root / "otb" / name;
  std::vector<cv::Rect2d> truth;
  try {
    truth = attend::ReadOtbGroundTruth((folder / truth_file).string());
  } catch (const std::exception& e) {
    std::cerr << "tracking_bench: skipping OTB " << name << ": " << e.what() << "\n";
    return;
  }
  std::vector<fs::path> files;
  std::error_code error;
  for (const fs::directory_entry& entry : fs::directory_iterator(folder / "img", error)) {
    if (entry.path().extension() == ".jpg") files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  if (files.empty() || error) {
    std::cerr << "tracking_bench: skipping OTB " << name << ": no " << (folder / "img").string()
              << "/*.jpg\n";
    return;
  }
  auto frames = std::make_unique<Frames>();
  frames->name = "OTB " + name;
  frames->source = "OTB-2013 " + name + " (Wu, Lim, Yang 2013)";
  for (const fs::path& file : files) {
    cv::Mat image = cv::imread(file.string(), cv::IMREAD_COLOR);
    if (image.empty()) {
      std::cerr << "tracking_bench: skipping OTB " << name << ": cannot read " << file << "\n";
      return;
    }
    frames->images.push_back(image);
  }
  truth.resize(frames->images.size());
  Task task;
  task.frames = frames.get();
  task.object = truth_file == "groundtruth_rect.txt" ? name : name + " (" + truth_file + ")";
  task.group = "OTB";
  task.first = 0;
  task.truth = truth;
  task.init = Rounded(truth[0]);
  CountHidden(&task);
  tasks->push_back(task);
  all->push_back(std::move(frames));
}

// ---------------------------------------------------------------------------------------------
// Methods

class Method {
 public:
  virtual ~Method() = default;
  // Starts on `frame`; false when the method cannot start there. `box` is where it starts.
  virtual bool Init(const cv::Mat& frame, const cv::Rect& init, cv::Rect2d* box) = 0;
  // The timed update. Sets `box` to the method's answer for this frame; returns whether the
  // method says it found the target.
  virtual bool Update(const cv::Mat& frame, cv::Rect2d* box) = 0;
  // False once the method has given up for good (a lost BIP target): it is neither called nor
  // timed any more.
  virtual bool Active() const { return true; }
};

// Any kind through the tracker interface (tracker/target_tracker.h).
class InterfaceMethod final : public Method {
 public:
  explicit InterfaceMethod(const attend::TargetTrackerOptions& options) : options_(options) {}
  bool Init(const cv::Mat& frame, const cv::Rect& init, cv::Rect2d* box) override {
    tracker_ = attend::TargetTracker::Create(options_);
    id_ = tracker_->StartFromBox(frame, init);
    if (id_ < 0) return false;
    *box = cv::Rect2d(cv::boundingRect(tracker_->Mask(id_)));
    return true;
  }
  bool Update(const cv::Mat& frame, cv::Rect2d* box) override {
    results_.clear();
    tracker_->Track(frame, &results_);
    if (results_.empty()) {
      lost_ = true;
      *box = cv::Rect2d();
      return false;
    }
    const attend::TrackResult& result = results_[0];
    *box = cv::Rect2d(result.box);
    if (result.state == attend::TrackState::kLost) lost_ = true;
    return result.state == attend::TrackState::kFound;
  }
  bool Active() const override { return !lost_; }

 private:
  attend::TargetTrackerOptions options_;
  std::unique_ptr<attend::TargetTracker> tracker_;
  std::vector<attend::TrackResult> results_;
  int id_ = -1;
  bool lost_ = false;
};

class CamShiftMethod final : public Method {
 public:
  bool Init(const cv::Mat& frame, const cv::Rect& init, cv::Rect2d* box) override {
    image_ = cv::Rect(0, 0, frame.cols, frame.rows);
    window_ = init & image_;
    if (window_.empty()) return false;
    HueAndMask(frame);
    const int channels[] = {0};
    const int bins[] = {kHueBins};
    const float hue_range[] = {0, 180};
    const float* ranges[] = {hue_range};
    const cv::Mat hue_roi = hue_(window_), mask_roi = mask_(window_);
    cv::calcHist(&hue_roi, 1, channels, mask_roi, histogram_, 1, bins, ranges);
    cv::normalize(histogram_, histogram_, 0, 255, cv::NORM_MINMAX);
    *box = cv::Rect2d(window_);
    return true;
  }
  bool Update(const cv::Mat& frame, cv::Rect2d* box) override {
    HueAndMask(frame);
    const int channels[] = {0};
    const float hue_range[] = {0, 180};
    const float* ranges[] = {hue_range};
    cv::calcBackProject(&hue_, 1, channels, histogram_, back_projection_, ranges);
    back_projection_ &= mask_;
    if (window_.area() <= 1) {
      // camshiftdemo's recovery: a window that collapsed grows back around where it was.
      const int r = (std::min(image_.width, image_.height) + 5) / 6;
      window_ = cv::Rect(window_.x - r, window_.y - r, 2 * r, 2 * r) & image_;
    }
    const cv::RotatedRect found =
        cv::CamShift(back_projection_, window_,
                     cv::TermCriteria(cv::TermCriteria::EPS | cv::TermCriteria::COUNT, 10, 1));
    const cv::Rect bounds = found.boundingRect() & image_;
    if (bounds.empty()) {
      *box = last_;
      return false;
    }
    last_ = cv::Rect2d(bounds);
    *box = last_;
    return true;
  }

 private:
  void HueAndMask(const cv::Mat& frame) {
    cv::cvtColor(frame, hsv_, cv::COLOR_BGR2HSV);
    cv::inRange(hsv_, cv::Scalar(0, kMinSaturation, kMinValue), cv::Scalar(180, 256, 256), mask_);
    hue_.create(hsv_.size(), CV_8UC1);
    const int from_to[] = {0, 0};
    cv::mixChannels(&hsv_, 1, &hue_, 1, from_to, 1);
  }

  cv::Rect image_;
  cv::Rect window_;
  cv::Rect2d last_;
  cv::Mat hsv_, hue_, mask_, histogram_, back_projection_;
};

const char* const kMethodNames[] = {"BIP thesis (ours)", "BIP bounded (ours)", "CSRT", "KCF",
                                    "CamShift", "BIP bounded + occlusion (ours)"};
constexpr int kMethods = 6;
constexpr int kBipThesis = 0, kCsrt = 2;

attend::TargetTrackerOptions KindOptions(attend::TrackerKind kind,
                                         attend::TrackerMode mode = attend::TrackerMode::kThesis) {
  attend::TargetTrackerOptions options;
  options.kind = kind;
  options.bip.mode = mode;
  // Longer than any sequence: a failing OpenCV tracker keeps its last box (the OTB rule).
  options.opencv.lost_frames = 1000000;  // the largest allowed, above any sequence's length
  // As before the interface: KCF never reports a weak response as a failure.
  options.opencv.kcf_detect_thresh = 0.f;
  return options;
}

std::vector<std::unique_ptr<Method>> MakeMethods() {
  using attend::TrackerKind;
  std::vector<std::unique_ptr<Method>> methods;
  methods.push_back(std::make_unique<InterfaceMethod>(KindOptions(TrackerKind::kBip)));
  methods.push_back(std::make_unique<InterfaceMethod>(
      KindOptions(TrackerKind::kBip, attend::TrackerMode::kBounded)));
  methods.push_back(std::make_unique<InterfaceMethod>(KindOptions(TrackerKind::kCsrt)));
  methods.push_back(std::make_unique<InterfaceMethod>(KindOptions(TrackerKind::kKcf)));
  methods.push_back(std::make_unique<CamShiftMethod>());
  // The bounded mode with its occlusion rules (tracker.occlusion; docs/TRACKING.md, "Modes" 12).
  attend::TargetTrackerOptions occlusion =
      KindOptions(TrackerKind::kBip, attend::TrackerMode::kBounded);
  occlusion.bip.occlusion = true;
  methods.push_back(std::make_unique<InterfaceMethod>(occlusion));
  return methods;
}

// Frames with a true box in which `predicted` has more than four times its area.
int Oversize(const std::vector<cv::Rect2d>& predicted, const std::vector<cv::Rect2d>& truth) {
  int frames = 0;
  for (size_t f = 0; f < truth.size() && f < predicted.size(); ++f) {
    if (truth[f].empty()) continue;
    if (predicted[f].area() > 4.0 * truth[f].area()) ++frames;
  }
  return frames;
}

// ---------------------------------------------------------------------------------------------
// Single-target runs

struct MethodResult {
  bool started = false;
  attend::TrackingScores scores;
  double ms = 0.0;   // median over repetitions of the mean update time
  int reported = 0;  // updates that said "found"
  int updates = 0;   // updates made (a lost BIP target is not updated any more)
  int oversize = 0;  // frames whose box has more than 4x the true box's area
};

struct TaskResult {
  const Task* task = nullptr;
  MethodResult methods[kMethods];
};

TaskResult RunTask(const Task& task, int repeat) {
  TaskResult result;
  result.task = &task;
  const std::vector<cv::Mat>& images = task.frames->images;
  const int frames = static_cast<int>(images.size());
  std::vector<double> ms[kMethods];
  for (int round = 0; round < repeat; ++round) {
    std::vector<std::unique_ptr<Method>> methods = MakeMethods();
    std::vector<cv::Rect2d> predicted[kMethods];
    bool started[kMethods];
    double total[kMethods] = {};
    int reported[kMethods] = {};
    int updates[kMethods] = {};
    for (int m = 0; m < kMethods; ++m) {
      predicted[m].assign(frames, cv::Rect2d());
      started[m] = methods[m]->Init(images[task.first], task.init, &predicted[m][task.first]);
    }
    for (int f = task.first + 1; f < frames; ++f) {
      for (int k = 0; k < kMethods; ++k) {
        const int m = (f + k) % kMethods;
        if (!started[m] || !methods[m]->Active()) continue;
        const attend::Stopwatch watch;
        const bool found = methods[m]->Update(images[f], &predicted[m][f]);
        total[m] += watch.ElapsedMs();
        reported[m] += found ? 1 : 0;
        ++updates[m];
      }
    }
    for (int m = 0; m < kMethods; ++m) {
      if (!started[m]) continue;
      ms[m].push_back(updates[m] > 0 ? total[m] / updates[m] : 0.0);
      if (round > 0) continue;
      MethodResult& r = result.methods[m];
      r.started = true;
      r.scores = attend::ScoreTracking(predicted[m], task.truth);
      r.reported = reported[m];
      r.updates = updates[m];
      r.oversize = Oversize(predicted[m], task.truth);
    }
  }
  for (int m = 0; m < kMethods; ++m) result.methods[m].ms = Median(ms[m]);
  return result;
}

// ---------------------------------------------------------------------------------------------
// Several targets at once (thesis table 4.3)

struct Configuration {
  std::vector<int> objects;
  std::unique_ptr<attend::TargetTracker> tracker;  // kind bip
  int started = 0;
  std::vector<double> ms;          // TargetTracker::Track, per frame 1, 2, ...
  std::vector<double> segment_ms;  // its over-segmentation part
  std::vector<double> capture_ms;  // decoding the frame's PNG before it
  std::vector<int> searched;       // targets searched, per frame 1, 2, ...
  int found_last = 0;              // targets found in the last frame
};

struct CostRow {
  int targets = 0;
  int configurations = 0;
  double started = 0.0;     // mean targets that started
  double searched = 0.0;    // mean targets searched per frame
  double found_last = 0.0;  // mean targets found in the last frame
  double ms = 0.0;          // mean over configurations of the median ms/frame, every frame
  double window_ms = 0.0;   // the same over frames 1..window
  // Over frames 1..window, as thesis table 4.3 splits a frame: capture, over-segmentation,
  // matching (Track minus over-segmentation).
  double capture_ms = 0.0;
  double segment_ms = 0.0;
};

struct CostResult {
  std::string source;
  int frames = 0;
  // Frames 1..window: every started target of every configuration is still searched.
  int window = 0;
  std::vector<CostRow> rows;
  std::string failure;
};

// The frames 1..K in which every started target of `c` is searched.
int AllSearched(const Configuration& c) {
  int frames = 0;
  while (frames < static_cast<int>(c.searched.size()) && c.searched[frames] == c.started) {
    ++frames;
  }
  return frames;
}

double MeanOfFirst(const std::vector<double>& values, int count) {
  double sum = 0.0;
  for (int i = 0; i < count; ++i) sum += values[i];
  return count > 0 ? sum / count : 0.0;
}

CostResult RunCost(const std::string& path, int repeat) {
  CostResult result;
  const attend::Scene scene = attend::LoadScene(path);
  const attend::SceneRenderer renderer(scene);
  result.source = "sequences/" + fs::path(path).filename().string();
  std::vector<cv::Mat> images;
  std::vector<std::vector<uchar>> encoded;  // each frame as a PNG file holds it
  std::map<int, cv::Rect> start;
  for (int f = 0; f < scene.frames; ++f) {
    attend::RenderedFrame rendered = renderer.Render(f);
    images.push_back(rendered.left);
    encoded.emplace_back();
    cv::imencode(".png", rendered.left, encoded.back());
    if (f != 0) continue;
    for (const attend::GtObject& object : rendered.objects) start[object.id] = Rounded(object.box);
  }
  result.frames = static_cast<int>(images.size());
  const int updates = result.frames - 1;
  // 1 target: each object alone; 3: every run of three consecutive objects (cyclic), so each
  // object is in three of them; 8: all of them.
  std::vector<std::vector<int>> sets;
  const int n = static_cast<int>(kCrowdObjects.size());
  for (const int id : kCrowdObjects) sets.push_back({id});
  for (int i = 0; i < n; ++i) {
    sets.push_back({kCrowdObjects[i], kCrowdObjects[(i + 1) % n], kCrowdObjects[(i + 2) % n]});
  }
  sets.push_back(kCrowdObjects);

  std::vector<std::vector<Configuration>> rounds;
  for (int round = 0; round < repeat; ++round) {
    std::vector<Configuration> configurations(sets.size());
    for (size_t c = 0; c < sets.size(); ++c) {
      configurations[c].objects = sets[c];
      configurations[c].tracker = attend::TargetTracker::Create(KindOptions(attend::TrackerKind::kBip));
      for (const int id : sets[c]) {
        if (configurations[c].tracker->StartFromBox(images[0], start[id]) >= 0) {
          ++configurations[c].started;
        }
      }
    }
    std::vector<attend::TrackResult> results;
    for (int f = 1; f < result.frames; ++f) {
      for (size_t k = 0; k < configurations.size(); ++k) {
        Configuration& c = configurations[(f + k) % configurations.size()];
        c.searched.push_back(static_cast<int>(c.tracker->ids().size()));
        results.clear();
        // Capture: the frame decoded from its PNG, as `attend track` reads a sequence.
        const attend::Stopwatch capture;
        const cv::Mat frame = cv::imdecode(encoded[f], cv::IMREAD_COLOR);
        c.capture_ms.push_back(capture.ElapsedMs());
        const attend::Stopwatch watch;
        c.tracker->Track(frame, &results);
        c.ms.push_back(watch.ElapsedMs());
        c.segment_ms.push_back(c.tracker->segmentation_milliseconds());
        if (f == result.frames - 1) {
          c.found_last = static_cast<int>(std::count_if(
              results.begin(), results.end(),
              [](const attend::TrackResult& r) { return r.state == attend::TrackState::kFound; }));
        }
      }
    }
    for (Configuration& c : configurations) c.tracker.reset();
    rounds.push_back(std::move(configurations));
  }
  result.window = updates;
  for (const Configuration& c : rounds[0]) result.window = std::min(result.window, AllSearched(c));

  for (const int size : {1, 3, n}) {
    CostRow row;
    row.targets = size;
    for (size_t c = 0; c < sets.size(); ++c) {
      if (static_cast<int>(sets[c].size()) != size) continue;
      ++row.configurations;
      std::vector<double> all, window, capture, segment;
      for (const std::vector<Configuration>& round : rounds) {
        all.push_back(MeanOfFirst(round[c].ms, updates));
        window.push_back(MeanOfFirst(round[c].ms, result.window));
        capture.push_back(MeanOfFirst(round[c].capture_ms, result.window));
        segment.push_back(MeanOfFirst(round[c].segment_ms, result.window));
      }
      row.ms += Median(all);
      row.window_ms += Median(window);
      row.capture_ms += Median(capture);
      row.segment_ms += Median(segment);
      const Configuration& first = rounds[0][c];
      row.started += first.started;
      double searched = 0.0;
      for (const int count : first.searched) searched += count;
      row.searched += searched / updates;
      row.found_last += first.found_last;
    }
    if (row.configurations == 0) continue;
    row.ms /= row.configurations;
    row.window_ms /= row.configurations;
    row.capture_ms /= row.configurations;
    row.segment_ms /= row.configurations;
    row.started /= row.configurations;
    row.searched /= row.configurations;
    row.found_last /= row.configurations;
    result.rows.push_back(row);
  }
  return result;
}

// ---------------------------------------------------------------------------------------------
// Report

std::string Ratio(double numerator, double denominator) {
  return denominator > 0.0 ? Fixed(numerator / denominator, 1) + "x" : "n/a";
}

// Means over the tasks of a group (all tasks when `group` is empty).
struct GroupMeans {
  int tasks = 0;
  double auc[kMethods] = {};
  double precision[kMethods] = {};
  double ms[kMethods] = {};
  int oversize[kMethods] = {};  // summed over the tasks
};

GroupMeans Means(const std::vector<TaskResult>& results, const std::string& group) {
  GroupMeans means;
  for (const TaskResult& r : results) {
    if (!group.empty() && r.task->group != group) continue;
    bool all_started = true;
    for (const MethodResult& m : r.methods) all_started = all_started && m.started;
    if (!all_started) continue;
    ++means.tasks;
    for (int m = 0; m < kMethods; ++m) {
      means.auc[m] += r.methods[m].scores.success_auc;
      means.precision[m] += r.methods[m].scores.precision_20;
      means.ms[m] += r.methods[m].ms;
      means.oversize[m] += r.methods[m].oversize;
    }
  }
  for (int m = 0; m < kMethods && means.tasks > 0; ++m) {
    means.auc[m] /= means.tasks;
    means.precision[m] /= means.tasks;
    means.ms[m] /= means.tasks;
  }
  return means;
}

void WriteReport(const Options& options, const std::vector<TaskResult>& results,
                 const CostResult& cost, std::ostream& out) {
  out << "Command: `" << options.command_line << "`. Date: " << UtcNow() << "; CPU: " << CpuModel()
      << "; nproc: " << std::thread::hardware_concurrency() << "; OpenCV " << CV_VERSION
      << "; cv::getNumThreads() = " << cv::getNumThreads() << "; repetitions: " << options.repeat
      << " (ms/frame: median over them of the mean update time; the methods take turns frame by "
         "frame).\n\n";
  out << "Every method but CamShift runs through the tracker interface (TargetTracker, "
         "tracker/target_tracker.h). BIP: kind bip, TrackerOptions defaults (thesis values) with "
         "tracker.mode thesis, and again with tracker.mode bounded. CSRT, KCF: kinds csrt and kcf, "
         "OpenCV default Params but KCF's detect_thresh 0 (tracker.kcf_detect_thresh), lost_frames "
         "above any sequence's length. CamShift: hue histogram of "
      << kHueBins << " bins in the initial box over pixels with S >= " << kMinSaturation
      << " and V >= " << kMinValue
      << " (OpenCV HSV), back-projection masked the same way, cv::CamShift with 10 iterations / "
         "1 px; its box is the rotated rectangle's bounding box. A method that reports failure "
         "keeps its last box; a lost BIP target scores 0 in the remaining frames and is not "
         "updated or timed any more (reports found: found / updates made). Synthetic "
         "sequences start on the first frame where the object is at least 95 % visible, from "
         "its true box; frames where it is hidden are not scored.\n\n";

  out << "### Per sequence\n\n";
  out << "| sequence | target | frames | start | hidden | method | success AUC | precision@20 | "
         "mean IoU | reports found | box > 4x truth | ms/frame |\n";
  out << "|---|---|---:|---:|---:|---|---:|---:|---:|---:|---:|---:|\n";
  for (const TaskResult& r : results) {
    const Task& t = *r.task;
    for (int m = 0; m < kMethods; ++m) {
      const MethodResult& mr = r.methods[m];
      out << "| " << t.frames->name << " | " << t.object << " | " << t.frames->images.size()
          << " | " << t.first << " " << t.init.x << "," << t.init.y << "," << t.init.width << ","
          << t.init.height << " | " << t.hidden << " | " << kMethodNames[m] << " | ";
      if (!mr.started) {
        out << "did not start | | | | | |\n";
        continue;
      }
      out << Fixed(mr.scores.success_auc, 3) << " | " << Fixed(mr.scores.precision_20, 3) << " | "
          << Fixed(mr.scores.mean_iou, 3) << " | " << mr.reported << "/" << mr.updates << " | "
          << mr.oversize << " | " << Fixed(mr.ms, 2) << " |\n";
    }
  }

  out << "\n### Means per group\n\n";
  out << "| group | targets | method | success AUC | precision@20 | box > 4x truth (frames, "
         "summed) | ms/frame | ms / BIP thesis ms |\n";
  out << "|---|---:|---|---:|---:|---:|---:|---:|\n";
  for (const std::string group : {"synthetic occlusions", "synthetic lab", "OTB", ""}) {
    const GroupMeans means = Means(results, group);
    if (means.tasks == 0) continue;
    const std::string label = group.empty()         ? std::string("all")
                              : group == "OTB"      ? "OTB (" + std::to_string(means.tasks) + ")"
                                                    : group;
    for (int m = 0; m < kMethods; ++m) {
      out << "| " << label << " | " << means.tasks << " | " << kMethodNames[m] << " | "
          << Fixed(means.auc[m], 3) << " | " << Fixed(means.precision[m], 3) << " | "
          << means.oversize[m] << " | " << Fixed(means.ms[m], 2) << " | "
          << Ratio(means.ms[m], means.ms[kBipThesis]) << " |\n";
    }
  }

  // SPEC 5: at least 10x faster than CSRT with a success AUC at least as high on homogeneous
  // objects under occlusion.
  const GroupMeans occlusions = Means(results, "synthetic occlusions");
  if (occlusions.tasks > 0) {
    const int b = kBipThesis, c = kCsrt;
    const double speed = occlusions.ms[b] > 0.0 ? occlusions.ms[c] / occlusions.ms[b] : 0.0;
    int faster = 0, as_good = 0;
    for (const TaskResult& r : results) {
      if (r.task->group != "synthetic occlusions" || !r.methods[b].started ||
          !r.methods[c].started) {
        continue;
      }
      if (r.methods[c].ms >= 10.0 * r.methods[b].ms) ++faster;
      if (r.methods[b].scores.success_auc >= r.methods[c].scores.success_auc) ++as_good;
    }
    out << "\nSPEC 5, homogeneous objects under occlusion (occlusions.yaml, " << occlusions.tasks
        << " targets): CSRT takes " << Fixed(speed, 1) << "x the BIP (thesis) tracker's time on average ("
        << faster << " of " << occlusions.tasks << " targets at least 10x); mean success AUC "
        << Fixed(occlusions.auc[b], 3) << " (BIP thesis) against " << Fixed(occlusions.auc[c], 3)
        << " (CSRT), BIP at least as high on " << as_good << " of " << occlusions.tasks
        << " targets. Target "
        << (speed >= 10.0 && occlusions.auc[b] >= occlusions.auc[c] ? "met" : "not met")
        << " (on the means).\n";
  }

  if (cost.source.empty()) {
    out << "\nSeveral targets in one pyramid: " << cost.failure << "\n";
    return;
  }
  out << "\n### Several targets in one pyramid (" << cost.source << ", " << cost.frames
      << " frames)\n\n";
  if (!cost.failure.empty()) {
    out << "Failed: " << cost.failure << "\n";
    return;
  }
  out << "Objects ";
  for (size_t i = 0; i < kCrowdObjects.size(); ++i) out << (i ? ", " : "") << kCrowdObjects[i];
  out << " (not skin, present at frame 0), started at frame 0 from their true boxes. 1 target: "
         "each object alone; 3: each run of three consecutive objects of that list (cyclic); "
         "8: all. All configurations take turns frame by frame. ms/frame: TargetTracker::Track "
         "(kind bip, mode thesis), "
         "mean over the configurations of the median over repetitions, over every frame (a lost "
         "target stops costing; searched: targets searched per frame on average) and over frames "
         "1.."
      << cost.window
      << ", in which every started target of every configuration is still searched: the "
         "comparison of SPEC 5.\n\n";
  out << "| targets | configurations | started | searched per frame | found in the last frame "
         "| ms/frame, frames 1.."
      << cost.window << " | ratio to 1 target | ms/frame, all frames | ratio to 1 target |\n";
  out << "|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  const double one = cost.rows.empty() ? 0.0 : cost.rows[0].ms;
  const double one_window = cost.rows.empty() ? 0.0 : cost.rows[0].window_ms;
  for (const CostRow& row : cost.rows) {
    out << "| " << row.targets << " | " << row.configurations << " | " << Fixed(row.started, 2)
        << " | " << Fixed(row.searched, 2) << " | " << Fixed(row.found_last, 2) << " | "
        << Fixed(row.window_ms, 2) << " | " << Ratio(row.window_ms, one_window) << " | "
        << Fixed(row.ms, 2) << " | " << Ratio(row.ms, one) << " |\n";
  }
  out << "\nThe same frames 1.." << cost.window
      << " split as thesis table 4.3 splits a frame: capture (here: decoding the frame's PNG, "
         "as `attend track` reads a sequence; the thesis grabbed camera frames), "
         "over-segmentation (colour conversion and pyramids, "
         "TargetTracker::segmentation_milliseconds), matching (the rest of Track: localisation, "
         "refinement, template and ROI update). The thesis's initialization column (structures "
         "set up every frame) has no counterpart: the tracker keeps its buffers.\n\n";
  out << "| targets | capture | over-segmentation | matching | Track | ratio to 1 target | "
         "total | ratio to 1 target |\n";
  out << "|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  const double one_total = cost.rows.empty() ? 0.0 : cost.rows[0].capture_ms + one_window;
  for (const CostRow& row : cost.rows) {
    const double total = row.capture_ms + row.window_ms;
    out << "| " << row.targets << " | " << Fixed(row.capture_ms, 2) << " | "
        << Fixed(row.segment_ms, 2) << " | " << Fixed(row.window_ms - row.segment_ms, 2) << " | "
        << Fixed(row.window_ms, 2) << " | " << Ratio(row.window_ms, one_window) << " | "
        << Fixed(total, 2) << " | " << Ratio(total, one_total) << " |\n";
  }
  for (const CostRow& row : cost.rows) {
    if (row.targets != 3 || one_window <= 0.0) continue;
    const double total = row.capture_ms + row.window_ms;
    out << "\nSPEC 5, three targets under 1.6x one (frames 1.." << cost.window
        << "): TargetTracker::Track alone " << Fixed(row.window_ms / one_window, 2) << "x, "
        << (row.window_ms / one_window < 1.6 ? "met" : "not met")
        << "; the whole frame with its capture, as thesis table 4.3 counts it, "
        << Fixed(total / one_total, 2) << "x, " << (total / one_total < 1.6 ? "met" : "not met")
        << ".\n";
  }
}

}  // namespace

int main(int argc, char** argv) {
  Options options;
  options.data_dir = ATTEND_SOURCE_ROOT "/../shared/data";
  options.home = ATTEND_SOURCE_ROOT;
  options.repeat = 3;
  const std::vector<std::string> known = {"occlusions", "lab",     "Couple", "Crossing",
                                          "Dog1",       "Jogging", "otb",    "crowd"};
  const int status = attend::bench::ParseBenchOptions(
      "tracking_bench", "the BIP tracker against CSRT, KCF and CamShift (docs/TRACKING.md)",
      "reference data folder holding otb/; sequences that are missing are skipped", argc, argv,
      &options,
      "run only these, comma-separated: occlusions, lab, Couple, Crossing, Dog1, Jogging, otb "
      "(the four OTB sequences), crowd (the several-targets cost); default: all");
  if (status >= 0) return status;
  cv::setNumThreads(1);
  std::vector<std::string> chosen;
  {
    std::stringstream list(options.sequences);
    for (std::string name; std::getline(list, name, ',');) {
      if (name.empty()) continue;
      if (std::find(known.begin(), known.end(), name) == known.end()) {
        std::cerr << "tracking_bench: --sequences: unknown '" << name << "'; choose from "
                  << "occlusions, lab, Couple, Crossing, Dog1, Jogging, otb, crowd\n";
        return 2;
      }
      chosen.push_back(name);
    }
  }
  const auto wanted = [&](const std::string& name, bool otb) {
    if (chosen.empty()) return true;
    for (const std::string& c : chosen) {
      if (c == name || (otb && c == "otb")) return true;
    }
    return false;
  };

  std::vector<std::unique_ptr<Frames>> frames;
  std::vector<Task> tasks;
  for (const SceneChoice& choice : kScenes) {
    if (!wanted(fs::path(choice.file).stem().string(), false)) continue;
    const std::string path = options.home + "/sequences/" + choice.file;
    try {
      AddScene(path, choice.objects, &frames, &tasks);
    } catch (const std::exception& e) {
      std::cerr << "tracking_bench: skipping " << path << ": " << e.what() << "\n";
    }
  }
  const fs::path root = fs::path(options.data_dir).lexically_normal();
  if (!fs::is_directory(root / "otb")) {
    std::cerr << "tracking_bench: skipping the OTB sequences: " << (root / "otb").string()
              << " not found\n";
  } else {
    const std::pair<const char*, const char*> otb[] = {{"Couple", "groundtruth_rect.txt"},
                                                       {"Crossing", "groundtruth_rect.txt"},
                                                       {"Dog1", "groundtruth_rect.txt"},
                                                       {"Jogging", "groundtruth_rect.1.txt"}};
    for (const auto& [name, truth] : otb) {
      if (wanted(name, true)) AddOtb(root, name, truth, &frames, &tasks);
    }
  }
  if (tasks.empty()) {
    std::cerr << "tracking_bench: no sequences to run\n";
    return 1;
  }

  std::vector<TaskResult> results;
  for (const Task& task : tasks) {
    std::cerr << "tracking_bench: " << task.frames->name << " " << task.object << "\n";
    results.push_back(RunTask(task, options.repeat));
  }
  CostResult cost;
  const std::string crowd = options.home + "/sequences/crowd.yaml";
  if (wanted("crowd", false)) {
    std::cerr << "tracking_bench: several targets on " << crowd << "\n";
    try {
      cost = RunCost(crowd, options.repeat);
    } catch (const std::exception& e) {
      cost.failure = e.what();
    }
  } else {
    cost.failure = "not run (--sequences)";
  }

  std::ostringstream report;
  WriteReport(options, results, cost, report);
  std::cout << report.str();
  if (!options.markdown_path.empty()) {
    std::ofstream file(options.markdown_path);
    file << report.str();
    if (!file) {
      std::cerr << "tracking_bench: cannot write " << options.markdown_path << "\n";
      return 1;
    }
  }
  return 0;
}
