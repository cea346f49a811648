// Benchmark: the top-down channels of features/detectors.h on MOT sequences with ground truth,
// through the plugins themselves (the factories of `people` and `faces`, LazyFrameContext).
//
//   detector_bench [--set KEY=VALUE]... [--frames N] [--markdown FILE] [--shares]
//                  [--photos IMAGE...] [--overlays DIR] SEQUENCE_FOLDER...
//
// Each sequence (SEQ/left/*.jpg, SEQ/gt/objects.csv in the jpg's pixels) is read at attend's
// working size (sequence.resize fit in 320x240: 640x480 -> 320x240, 1224x370 -> 320x97, 960x540
// -> 320x180), its boxes scaled alike. On every frame from the second on (the first has no
// previous frame for the gated runs) these run, taking turns frame by frame (the first one
// rotates) so that load from other processes falls on all alike, on one thread:
//   people, model default and daimler, gate frame (every frame);
//   people, model default and daimler, gate attended, the attention regions being the ground
//     truth boxes of the previous frame: they stand for where attention looks when it is on
//     the people;
//   faces (the default cascade), gate frame.
// Each run's keys are the plugin's defaults with `gate` and `model` as above, then --set's.
// Scores: a detection matches an unmatched ground-truth box of its frame at IoU >= 0.5, most
// confident first; recall = matched / ground-truth boxes, precision = matched / detections.
// ms/frame is the mean time of FeatureMap::Compute (the map included); "share" is a gated
// run's time over the frame run's of the same model. Faces have no ground truth here: the
// table counts them, and those whose centre is in the top fifth of a person's box.
// --shares: the person inside each HOG window, measured: for the frame runs' detections that
// match, the medians of the truth box's width and height as shares of the window and of its
// centre's offset from the window's (the defaults of box_width and box_height come from it).
// --photos: faces (gate frame) on still images at the working size, counted, with the image
// and the boxes drawn to --overlays DIR when given.

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <opencv2/core.hpp>
#include <opencv2/core/utility.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "bench/bench_common.h"
#include "config/param_block.h"
#include "features/builtin.h"
#include "features/detectors.h"
#include "features/lazy_frame_context.h"
#include "io/ground_truth.h"
#include "io/sequence.h"
#include "util/box.h"
#include "util/error.h"
#include "util/timer.h"

namespace {

using attend::bench::Median;

namespace fs = std::filesystem;
using attend::Detection;

struct Run {
  std::string feature;  // people | faces
  std::string model;    // the people model, or "" for faces
  std::string gate;     // frame | attended
  std::unique_ptr<attend::FeatureMap> plugin;
  double ms = 0.0;
  int frames = 0, detections = 0, matched = 0, face_on_person = 0;
  // --shares: per matched window, truth width and height over the window's, centre offsets.
  std::vector<double> width_share, height_share, dx_share, dy_share;
  std::string Name() const {
    return feature == "faces" ? "faces" : feature + " " + model + ", " + gate;
  }
};

// The plugin `feature` with its defaults, `fixed` and then `sets` ("key=value").
std::unique_ptr<attend::FeatureMap> MakePlugin(const std::string& feature,
                                               const std::map<std::string, std::string>& fixed,
                                               const std::vector<std::string>& sets) {
  std::map<std::string, std::string> keys = fixed;
  for (const std::string& set : sets) {
    const size_t equals = set.find('=');
    if (equals == std::string::npos) throw attend::ConfigError("--set " + set + ": not KEY=VALUE");
    keys[set.substr(0, equals)] = set.substr(equals + 1);
  }
  std::string yaml;
  for (const auto& [key, value] : keys) yaml += key + ": " + value + "\n";
  attend::FeatureSpec spec;
  spec.name = feature;
  spec.params = attend::ParamBlock::Parse(yaml.empty() ? "{}" : yaml, "--set");
  attend::FeatureSetup setup;
  setup.stereo = false;
  return attend::BuiltinFeatures().Create(spec, setup);
}

// Scores `found` against `truth` (greedy, most confident first, IoU >= 0.5).
int Matches(const std::vector<Detection>& found, const std::vector<cv::Rect2d>& truth,
            std::vector<int>* truth_of) {
  std::vector<size_t> order(found.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t a, size_t b) { return found[a].confidence > found[b].confidence; });
  std::vector<char> taken(truth.size(), 0);
  truth_of->assign(found.size(), -1);
  int matched = 0;
  for (size_t i : order) {
    int best = -1;
    double best_iou = 0.5;
    for (size_t t = 0; t < truth.size(); ++t) {
      const double iou = attend::BoxIou(cv::Rect2d(found[i].box), truth[t]);
      if (!taken[t] && iou >= best_iou) best = static_cast<int>(t), best_iou = iou;
    }
    if (best >= 0) taken[best] = 1, (*truth_of)[i] = best, ++matched;
  }
  return matched;
}

struct Sequence {
  std::string name;
  cv::Size native, size;
  std::vector<cv::Mat> frames;
  std::vector<std::vector<cv::Rect2d>> truth;  // per frame, working pixels
  int truth_boxes = 0;                         // on the scored frames (1..)
};

Sequence ReadSequence(const std::string& folder, int max_frames) {
  Sequence sequence;
  attend::SequenceOptions options;
  options.source.folder = folder;
  if (max_frames > 0) options.last_frame = max_frames - 1;
  std::unique_ptr<attend::FrameSource> source = attend::OpenFrameSource(options);
  const attend::SequenceInfo& info = source->info();
  sequence.name = fs::path(folder).filename().string();
  if (sequence.name.empty()) sequence.name = fs::path(folder).parent_path().filename().string();
  sequence.native = info.native_size;
  sequence.size = info.size;
  attend::StereoFrame frame;
  while (source->Next(&frame)) sequence.frames.push_back(frame.left.clone());
  sequence.truth.resize(sequence.frames.size());
  for (const attend::GtObject& object :
       attend::ReadObjectsCsv((fs::path(folder) / "gt" / "objects.csv").string())) {
    if (object.frame < 0 || object.frame >= static_cast<int>(sequence.frames.size())) continue;
    if (object.box.empty()) continue;
    const cv::Rect2d box(object.box.x * info.scale_x, object.box.y * info.scale_y,
                         object.box.width * info.scale_x, object.box.height * info.scale_y);
    sequence.truth[object.frame].push_back(box);
    if (object.frame > 0) ++sequence.truth_boxes;
  }
  return sequence;
}

std::vector<cv::Rect> Regions(const std::vector<cv::Rect2d>& boxes) {
  std::vector<cv::Rect> regions;
  for (const cv::Rect2d& box : boxes) {
    regions.push_back(
        cv::Rect(cvRound(box.x), cvRound(box.y), cvRound(box.width), cvRound(box.height)));
  }
  return regions;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> folders, sets, photos;
  std::string markdown_path, overlays;
  int max_frames = 0;
  bool shares = false;
  std::string command_line = "detector_bench";
  for (int i = 1; i < argc; ++i) command_line += std::string(" ") + argv[i];
  CLI::App app{"The people and faces channels on MOT sequences with ground truth",
               "detector_bench"};
  app.add_option("sequences", folders, "sequence folders (left/, gt/objects.csv)");
  app.add_option("--set", sets, "KEY=VALUE for every run's plugin entry (repeatable)")
      ->allow_extra_args(false)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  app.add_option("--frames", max_frames, "at most this many frames of each sequence; 0: all")
      ->check(CLI::Range(0, 100000));
  app.add_option("--markdown", markdown_path, "also write the report to FILE");
  app.add_flag("--shares", shares, "measure the person's share of the HOG window");
  app.add_option("--photos", photos, "still images to run faces on");
  app.add_option("--overlays", overlays, "draw the photos' faces into this folder");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }
  cv::setNumThreads(1);

  std::ostringstream report;
  report << "Command: `" << command_line << "`\n\n"
         << attend::bench::CpuModel() << ", one thread, " << attend::bench::UtcNow() << ".\n\n";
  try {
    std::vector<std::string> people_sets, face_sets;
    for (const std::string& set : sets) {
      // Keys of one channel only go to its runs.
      const std::string key = set.substr(0, set.find('='));
      const bool hog_only = key == "hit_threshold" || key == "stride" || key == "box_width" ||
                            key == "box_height" || key == "model";
      people_sets.push_back(set);
      if (!hog_only) face_sets.push_back(set);
    }
    if (!folders.empty()) {
      report << "| sequence | working size | frames | truth boxes | run | recall | precision | "
                "detections | ms/frame | share of frame's time |\n"
             << "|---|---|---|---|---|---|---|---|---|---|\n";
    }
    std::ostringstream shares_report, faces_report;
    std::map<std::string, Run> pooled;  // --shares: every sequence's windows, per model
    for (const std::string& folder : folders) {
      const Sequence sequence = ReadSequence(folder, max_frames);
      std::vector<Run> runs;
      for (const char* gate : {"frame", "attended"}) {
        for (const char* model : {"default", "daimler"}) {
          Run run;
          run.feature = "people";
          run.model = model;
          run.gate = gate;
          std::map<std::string, std::string> fixed = {{"gate", gate}, {"model", model}};
          if (shares) fixed["box_width"] = "1", fixed["box_height"] = "1";
          run.plugin = MakePlugin("people", fixed, people_sets);
          runs.push_back(std::move(run));
        }
      }
      if (!shares) {
        Run faces;
        faces.feature = "faces";
        faces.gate = "frame";
        faces.plugin = MakePlugin("faces", {{"gate", "frame"}}, face_sets);
        runs.push_back(std::move(faces));
      }
      for (Run& run : runs) {
        run.plugin->BeginSequence({sequence.name, sequence.size, false, 0});
      }
      attend::LazyFrameContext context;
      cv::Mat map;
      std::vector<int> truth_of;
      for (size_t f = 0; f < sequence.frames.size(); ++f) {
        context.Reset(static_cast<int>(f), sequence.frames[f]);
        for (size_t k = 0; k < runs.size(); ++k) {
          Run& run = runs[(k + f) % runs.size()];
          context.set_attention_regions(f > 0 && run.gate == "attended"
                                            ? Regions(sequence.truth[f - 1])
                                            : std::vector<cv::Rect>());
          attend::Stopwatch watch;
          run.plugin->Compute(context, &map);
          const double ms = watch.ElapsedMs();
          if (f == 0) continue;
          run.ms += ms;
          ++run.frames;
          const std::vector<Detection>& found = run.plugin->detections();
          run.detections += static_cast<int>(found.size());
          const std::vector<cv::Rect2d>& truth = sequence.truth[f];
          if (run.feature == "faces") {
            for (const Detection& face : found) {
              const cv::Point2d centre(face.box.x + 0.5 * face.box.width,
                                       face.box.y + 0.5 * face.box.height);
              for (const cv::Rect2d& person : truth) {
                if (cv::Rect2d(person.x, person.y, person.width, person.height / 5)
                        .contains(centre)) {
                  ++run.face_on_person;
                  break;
                }
              }
            }
            continue;
          }
          if (shares) {
            // The window is the box here; a truth box matches its window at IoU >= 0.3
            // (a person fills about half of it).
            for (const Detection& window : found) {
              double best = 0.3;
              const cv::Rect2d* match = nullptr;
              for (const cv::Rect2d& person : truth) {
                const double iou = attend::BoxIou(cv::Rect2d(window.box), person);
                if (iou >= best) best = iou, match = &person;
              }
              if (match == nullptr) continue;
              ++run.matched;
              run.width_share.push_back(match->width / window.box.width);
              run.height_share.push_back(match->height / window.box.height);
              run.dx_share.push_back(
                  (match->x + 0.5 * match->width - window.box.x - 0.5 * window.box.width) /
                  window.box.width);
              run.dy_share.push_back(
                  (match->y + 0.5 * match->height - window.box.y - 0.5 * window.box.height) /
                  window.box.height);
            }
            continue;
          }
          run.matched += Matches(found, truth, &truth_of);
        }
      }
      const double frame_ms[2] = {runs[0].ms / std::max(1, runs[0].frames),
                                  runs[1].ms / std::max(1, runs[1].frames)};
      for (size_t k = 0; k < runs.size(); ++k) {
        const Run& run = runs[k];
        const double ms = run.ms / std::max(1, run.frames);
        if (shares) {
          if (run.gate != "frame") continue;
          Run& all = pooled[run.model];
          all.matched += run.matched;
          for (auto [to, from] : {std::pair{&all.width_share, &run.width_share},
                                  {&all.height_share, &run.height_share},
                                  {&all.dx_share, &run.dx_share},
                                  {&all.dy_share, &run.dy_share}}) {
            to->insert(to->end(), from->begin(), from->end());
          }
          shares_report << "| " << sequence.name << " | " << run.model << " | " << run.matched
                        << " | " << attend::bench::Fixed(Median(run.width_share), 3) << " | "
                        << attend::bench::Fixed(Median(run.height_share), 3) << " | "
                        << attend::bench::Fixed(Median(run.dx_share), 3) << " | "
                        << attend::bench::Fixed(Median(run.dy_share), 3) << " |\n";
          continue;
        }
        if (run.feature == "faces") {
          faces_report << "| " << sequence.name << " | " << sequence.size.width << "x"
                       << sequence.size.height << " | " << run.frames << " | " << run.detections
                       << " | " << run.face_on_person << " | " << attend::bench::Fixed(ms, 2)
                       << " |\n";
          continue;
        }
        const double recall = sequence.truth_boxes > 0
                                  ? static_cast<double>(run.matched) / sequence.truth_boxes
                                  : 0.0;
        const double precision =
            run.detections > 0 ? static_cast<double>(run.matched) / run.detections : 0.0;
        report << "| " << sequence.name << " | " << sequence.size.width << "x"
               << sequence.size.height << " | " << run.frames << " | " << sequence.truth_boxes
               << " | " << run.Name() << " | " << attend::bench::Fixed(recall, 3) << " | "
               << attend::bench::Fixed(precision, 3) << " | " << run.detections << " | "
               << attend::bench::Fixed(ms, 2) << " | "
               << (run.gate == "attended" ? attend::bench::Fixed(ms / frame_ms[k % 2], 3) : "")
               << " |\n";
      }
      std::cerr << "[detector_bench] " << sequence.name << " done\n";
    }
    if (shares) {
      report << "\nThe person in the HOG window (medians over matched windows, frame gate):\n\n"
             << "| sequence | model | windows | truth width / window | truth height / window "
                "| centre dx / width | centre dy / height |\n"
             << "|---|---|---|---|---|---|---|\n"
             << shares_report.str();
      for (const auto& [model, run] : pooled) {
        report << "| all | " << model << " | " << run.matched << " | "
               << attend::bench::Fixed(Median(run.width_share), 3) << " | "
               << attend::bench::Fixed(Median(run.height_share), 3) << " | "
               << attend::bench::Fixed(Median(run.dx_share), 3) << " | "
               << attend::bench::Fixed(Median(run.dy_share), 3) << " |\n";
      }
    } else if (!folders.empty()) {
      report << "\nfaces (gate frame) on the same frames:\n\n"
             << "| sequence | working size | frames | faces | centre in the top fifth of a "
                "person | ms/frame |\n"
             << "|---|---|---|---|---|---|\n"
             << faces_report.str();
    }
    if (!photos.empty()) {
      report << "\nfaces (gate frame) on photographs at the working size:\n\n"
             << "| photograph | working size | faces | confidences | ms |\n|---|---|---|---|---|\n";
      std::unique_ptr<attend::FeatureMap> faces =
          MakePlugin("faces", {{"gate", "frame"}}, face_sets);
      attend::SequenceOptions size_options;
      for (size_t i = 0; i < photos.size(); ++i) {
        const cv::Mat native = attend::ReadFrameFile(static_cast<int>(i), photos[i]);
        const cv::Mat image =
            attend::ToWorkingSize(native, attend::WorkingSize(size_options, native.size()));
        faces->BeginSequence({photos[i], image.size(), false, 0});
        attend::LazyFrameContext context;
        context.Reset(0, image);
        cv::Mat map;
        attend::Stopwatch watch;
        faces->Compute(context, &map);
        const double ms = watch.ElapsedMs();
        std::string confidences;
        cv::Mat overlay = image.clone();
        for (const Detection& face : faces->detections()) {
          confidences +=
              (confidences.empty() ? "" : " ") + attend::bench::Fixed(face.confidence, 2);
          cv::rectangle(overlay, face.box, cv::Scalar(0, 255, 0), 1);
        }
        report << "| " << fs::path(photos[i]).filename().string() << " | " << image.cols << "x"
               << image.rows << " | " << faces->detections().size() << " | " << confidences << " | "
               << attend::bench::Fixed(ms, 2) << " |\n";
        if (!overlays.empty()) {
          fs::create_directories(overlays);
          cv::imwrite((fs::path(overlays) / fs::path(photos[i]).filename()).string(), overlay);
        }
      }
    }
  } catch (const attend::Error& e) {
    std::cerr << "detector_bench: " << e.what() << "\n";
    return 2;
  }
  std::cout << report.str();
  if (!markdown_path.empty()) std::ofstream(markdown_path) << report.str();
  return 0;
}
