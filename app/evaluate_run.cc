#include "app/evaluate_run.h"

#include <filesystem>
#include <fstream>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <sstream>
#include <vector>

#include "eval/depth_scores.h"
#include "eval/disparity_scores.h"
#include "eval/kitti_truth.h"
#include "eval/landing.h"
#include "eval/lidar_depth.h"
#include "eval/mot_metrics.h"
#include "eval/rendered_truth.h"
#include "eval/run_evaluation.h"
#include "features/disparity_feature.h"
#include "io/ground_truth.h"
#include "io/kitti_layout.h"
#include "io/pfm.h"
#include "pipeline/options_io.h"
#include "stereo/disparity.h"
#include "util/error.h"
#include "util/file_checks.h"
#include "util/json_text.h"

namespace attend {

namespace {

namespace fs = std::filesystem;

// Boxes in frames.jsonl are in input pixels (SPEC 3.3) since summary.json has "pixels". A run
// written before, at a working size other than the input size, holds working pixels, which
// would score against input-pixel ground truth as if nothing were attended: refuse it.
void CheckSummaryPixels(const fs::path& path, const nlohmann::json& summary);

void CheckRecordsInInputPixels(const fs::path& run) {
  const fs::path path = run / "summary.json";
  std::error_code error;
  // An interrupted run may lack it; its frames are still input pixels.
  if (!fs::exists(path, error)) return;
  const std::string text = ReadRegularFile(path.string(), "the run's summary",
                                           ExitStatus::kBadInput, kMaxConfigBytes);
  try {
    CheckSummaryPixels(path, nlohmann::json::parse(text));
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    // Malformed JSON, or a field of another type (`"pixels": 5`).
    throw InputError(path.string() + ": not a run summary (" + e.what() + ")");
  }
}

void CheckSummaryPixels(const fs::path& path, const nlohmann::json& summary) {
  if (!summary.is_object()) throw std::runtime_error("not a JSON object");
  if (summary.contains("pixels")) {
    const std::string records = summary["pixels"].value("records", "");
    if (records != "input") {
      throw InputError(path.string() + ": pixels.records is '" + records +
                       "', but attend eval scores boxes in input pixels");
    }
    return;
  }
  if (!summary.contains("sequence")) return;
  const nlohmann::json& sequence = summary["sequence"];
  if (!sequence.contains("native_size") || !sequence.contains("size")) return;
  if (sequence["native_size"] != sequence["size"]) {
    throw InputError(path.string() + ": this run was written before attend recorded boxes in " +
                     "input pixels; its boxes are in working pixels (" +
                     JsonText(sequence["size"]) + ", input " + JsonText(sequence["native_size"]) +
                     "), so it cannot be scored against the ground truth: run it again");
  }
}

// The disparity maps dumped by the run (RUN/features/disparity/*.pfm, in [0, 1], at the
// working size) against gt/disparity/*.pfm (input size and pixels): mean bad-pixel rates over
// the frames that have both. A map at another size is resized to the ground truth's (nearest
// neighbour) and its disparities scaled by the width ratio, so scores are in input pixels.
nlohmann::ordered_json DisparityScores(const std::string& run, const std::string& gt,
                                       const AttendOptions& options) {
  const fs::path maps = fs::path(run) / "features" / "disparity";
  const fs::path truth = fs::path(gt) / "disparity";
  if (!fs::is_directory(maps) || !fs::is_directory(truth)) return nullptr;
  int max_disparity = DisparityOptions{}.max_disparity;
  for (const FeatureSpec& spec : options.features) {
    if (spec.name == "disparity") max_disparity = ReadDisparityOptions(spec.params).max_disparity;
  }
  double bad1 = 0.0, bad2 = 0.0;
  int frames = 0;
  for (const auto& entry : fs::directory_iterator(maps)) {
    if (entry.path().extension() != ".pfm") continue;
    const fs::path gt_path = truth / entry.path().filename();
    if (!fs::exists(gt_path)) continue;
    cv::Mat map = ReadPfmOneChannel(entry.path().string(), "a disparity map");
    map *= static_cast<float>(max_disparity - 1);
    const cv::Mat ground_truth = ReadPfmOneChannel(gt_path.string(), "disparity ground truth");
    if (map.size() != ground_truth.size()) {
      // Working and input sizes share the aspect ratio up to rounding (resize fit or native);
      // a stretched run does not, and its disparity is not comparable pixel for pixel.
      const double ratio_x = static_cast<double>(ground_truth.cols) / map.cols;
      const double ratio_y = static_cast<double>(ground_truth.rows) / map.rows;
      if (std::abs(ratio_x - ratio_y) > 0.02 * ratio_x) {
        throw InputError(
            gt_path.string() + ": ground truth of " + std::to_string(ground_truth.cols) + "x" +
            std::to_string(ground_truth.rows) + " for a map of " + std::to_string(map.cols) + "x" +
            std::to_string(map.rows) + " (another aspect ratio)");
      }
      cv::Mat resized;
      cv::resize(map, resized, ground_truth.size(), 0, 0, cv::INTER_NEAREST);
      map = resized * ratio_x;
    }
    const BadPixelRates rates = EvaluateDisparity(map, ground_truth);
    bad1 += rates.bad1;
    bad2 += rates.bad2;
    ++frames;
  }
  if (frames == 0) return nullptr;
  return {{"frames", frames}, {"mean_bad1", bad1 / frames}, {"mean_bad2", bad2 / frames}};
}

// The MOTChallenge measures at one threshold, under the devkit's names (SPEC 4).
nlohmann::ordered_json MotJson(const MotScores& s) {
  return {{"match_iou", s.match_iou},
          {"objects", s.objects},
          {"objects_attended_whole", s.objects_attended_whole},
          {"attended_whole_fraction", s.attended_whole_fraction},
          {"targets_started", s.targets_started},
          {"ids_per_attended_object", s.ids_per_attended_object},
          {"purity", s.purity},
          {"IDF1", s.idf1},
          {"IDP", s.idp},
          {"IDR", s.idr},
          {"IDTP", s.idtp},
          {"IDFP", s.idfp},
          {"IDFN", s.idfn},
          {"MOTA", s.mota},
          {"MOTP", s.motp},
          {"GT", s.gt},
          {"FP", s.false_positives},
          {"FN", s.false_negatives},
          {"IDSW", s.id_switches},
          {"MT", s.mostly_tracked},
          {"PT", s.partly_tracked},
          {"ML", s.mostly_lost},
          {"Frag", s.fragmentations},
          {"ignored", s.ignored}};
}

// MOTChallenge's match (0.5) and attend eval's own (EvaluationOptions::match_iou, 0.3), keyed
// "iou_0.5" and "iou_0.3".
nlohmann::ordered_json MotReport(const std::vector<FrameRecord>& frames,
                                 const std::vector<GtObject>& truth) {
  nlohmann::ordered_json mot = nlohmann::ordered_json::object();
  for (const double match_iou : {0.5, EvaluationOptions{}.match_iou}) {
    MotOptions options;
    options.match_iou = match_iou;
    std::ostringstream key;
    key << "iou_" << match_iou;
    mot[key.str()] = MotJson(EvaluateMot(frames, truth, options));
  }
  return mot;
}

// The targets' disparity and depth errors (eval/depth_scores.h); -1 as null.
nlohmann::ordered_json DepthJson(const DepthScores& s) {
  auto value = [](double v) { return v < 0.0 ? nlohmann::ordered_json() : nlohmann::ordered_json(v); };
  return {{"match_iou", DepthScoreOptions{}.match_iou},
          {"matches", s.matches},
          {"median_abs_error_px", value(s.median_abs_error_px)},
          {"mean_abs_error_px", value(s.mean_abs_error_px)},
          {"share_within_0.25_px", value(s.share_within_quarter_px)},
          {"near_disparity_px", DepthScoreOptions{}.near_disparity},
          {"near_matches", s.near_matches},
          {"median_depth_error", value(s.median_depth_error)},
          {"share_depth_within_2_percent", value(s.share_depth_within_2_percent)},
          {"share_within_1_sd", value(s.share_within_1_sd)},
          {"share_within_2_sd", value(s.share_within_2_sd)}};
}

// The scene truth of the ground-truth folder `gt` for where attention lands (eval/landing.h),
// or none when it has no per-pixel truth: a rendered street scene (gt/classes/), read with its
// sequence folder, gt's parent (sequence.yaml's focal_px and baseline_m). A KITTI drive's
// (its LiDAR scans and labels) is SequenceSceneTruth's.
std::optional<SceneTruth> LoadSceneTruth(const std::string& gt) {
  if (HasRenderedTruth(gt)) {
    fs::path folder = fs::path(gt).lexically_normal();
    if (folder.filename().empty()) folder = folder.parent_path();  // "seq/gt/"
    return ReadRenderedTruth(folder.parent_path().string());
  }
  return std::nullopt;
}

// The targets' depth against the LiDAR (eval/lidar_depth.h); -1 as null.
nlohmann::ordered_json LidarDepthJson(const LidarDepthScores& s) {
  auto value = [](double v) {
    return v < 0.0 ? nlohmann::ordered_json() : nlohmann::ordered_json(v);
  };
  return {{"min_points", kMinLidarPoints},
          {"count", s.count},
          {"share_within_10_percent", value(s.share_within_10_percent)},
          {"median_relative_error", value(s.median_relative_error)},
          {"median_abs_error_m", value(s.median_abs_error_m)}};
}

// The KITTI sequence of a run whose source is one, when no other ground truth is asked for.
std::optional<KittiSequence> RunKittiSequence(const AttendOptions& options, const std::string& gt) {
  if (!gt.empty() || options.sequence.source.folder.empty()) return std::nullopt;
  return FindKittiSequence(options.sequence.source.folder);
}

}  // namespace

std::optional<SceneTruth> SequenceSceneTruth(const SourceSpec& source) {
  if (source.folder.empty()) return std::nullopt;
  const std::optional<KittiSequence> kitti = FindKittiSequence(source.folder);
  if (!kitti) return std::nullopt;
  return ReadKittiTruth(*kitti);
}

nlohmann::ordered_json EvaluateRunFolder(const std::string& run_dir, const std::string& gt_dir) {
  const fs::path run(run_dir);
  if (!fs::is_directory(run) || !fs::exists(run / "frames.jsonl")) {
    throw InputError(run_dir + ": not a run folder (no frames.jsonl)");
  }
  // The run's configuration is part of the run: a missing or broken one is bad input (exit
  // status 3), as for `attend compare`, not a configuration error of this command.
  const fs::path config_path = run / "config.yaml";
  if (!fs::exists(config_path)) {
    throw InputError(config_path.string() +
                     ": missing; a run folder holds the configuration it ran with");
  }
  AttendOptions options;
  try {
    options = LoadOptions(config_path.string(), {});
  } catch (const ConfigError& e) {
    throw InputError(e.what());
  }
  const std::optional<KittiSequence> kitti = RunKittiSequence(options, gt_dir);
  std::string gt = gt_dir;
  if (kitti) {
    gt = kitti->labels.empty() ? kitti->folder : kitti->labels;
  } else if (gt.empty()) {
    if (options.sequence.source.folder.empty()) {
      throw ConfigError(run_dir + ": the run's source is not a sequence folder; give --gt");
    }
    gt = (fs::path(options.sequence.source.folder) / "gt").string();
  }
  const fs::path objects = fs::path(gt) / "objects.csv";
  if (!kitti && !fs::exists(objects)) {
    throw InputError(objects.string() + ": no ground-truth objects");
  }
  CheckRecordsInInputPixels(run);
  const std::vector<FrameRecord> frames = ReadFrameRecords((run / "frames.jsonl").string());
  const std::vector<GtObject> truth =
      kitti ? ReadKittiObjects(*kitti) : ReadObjectsCsv(objects.string());
  const AttentionScores scores = EvaluateAttention(frames, truth);

  nlohmann::ordered_json per_object = nlohmann::ordered_json::array();
  for (const ObjectScore& object : scores.per_object) {
    per_object.push_back({{"id", object.id},
                          {"kind", object.kind},
                          {"first_visible", object.first_visible},
                          {"first_attended", object.first_attended < 0
                                                 ? nlohmann::ordered_json()
                                                 : nlohmann::ordered_json(object.first_attended)},
                          {"identity_switches", object.switches}});
  }
  nlohmann::ordered_json report = {{"run", run_dir},
                                   {"gt", gt},
                                   {"frames", scores.frames},
                                   {"objects", scores.objects},
                                   {"attended", scores.attended},
                                   {"coverage", scores.coverage},
                                   {"mean_latency", scores.mean_latency},
                                   {"revisits", scores.revisits},
                                   {"identity_switches", scores.identity_switches},
                                   {"mean_iou", scores.mean_iou},
                                   {"mot", MotReport(frames, truth)},
                                   {"per_object", per_object}};
  const nlohmann::ordered_json disparity = DisparityScores(run_dir, gt, options);
  if (!disparity.is_null()) report["disparity"] = disparity;
  const DepthScores depth = EvaluateTargetDepth(frames, truth);
  if (depth.matches > 0) report["target_depth"] = DepthJson(depth);
  // Where attention lands (eval/landing.h) against the per-pixel truth of a rendered street
  // scene or a KITTI sequence's LiDAR and labels, and for KITTI the depth against the LiDAR.
  std::optional<SceneTruth> scene =
      kitti ? SequenceSceneTruth(options.sequence.source) : LoadSceneTruth(gt);
  if (scene) {
    report["landing"] = LandingToJson(EvaluateLanding(frames, *scene));
    if (kitti) report["depth_lidar"] = LidarDepthJson(EvaluateLidarDepth(frames, *scene));
  }
  return report;
}

}  // namespace attend
