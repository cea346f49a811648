#include "eval/run_comparison.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <opencv2/imgproc.hpp>
#include <set>
#include <sstream>

#include "config/flat_values.h"
#include "eval/kitti_truth.h"
#include "eval/run_evaluation.h"
#include "io/ground_truth.h"
#include "io/pfm.h"
#include "util/error.h"
#include "util/file_checks.h"
#include "util/json_text.h"

namespace attend {

namespace {

namespace fs = std::filesystem;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

cv::Mat AsDouble(const cv::Mat& map) {
  ATTEND_CHECK(map.channels() == 1) << "saliency maps have one channel, not " << map.channels();
  cv::Mat out;
  map.convertTo(out, CV_64F);
  return out;
}

void CheckPair(const cv::Mat& p, const cv::Mat& q) {
  ATTEND_CHECK(!p.empty() && p.size() == q.size())
      << "maps of " << p.cols << "x" << p.rows << " and " << q.cols << "x" << q.rows;
}

// `map` divided by its sum; empty when the sum is zero.
cv::Mat SumNormalised(const cv::Mat& map) {
  cv::Mat m = AsDouble(map);
  const double sum = cv::sum(m)[0];
  if (sum == 0.0 || !std::isfinite(sum)) return {};
  return m / sum;
}

bool ReadsAsNumber(const std::string& text, double* value) {
  if (text.empty()) return false;
  const char* end = text.data() + text.size();
  const auto [ptr, error] = std::from_chars(text.data(), end, *value);
  return error == std::errc() && ptr == end;
}

bool SameValue(const std::string& a, const std::string& b) {
  if (a == b) return true;
  double x = 0.0, y = 0.0;
  return ReadsAsNumber(a, &x) && ReadsAsNumber(b, &y) && x == y;
}

// Per-frame greedy one-to-one matching of the visible targets of two frames by IoU.
std::vector<std::pair<int, int>> MatchFrame(const FrameRecord& a, const FrameRecord& b) {
  const auto visible = [](const TargetRecord& t) { return Visible(t.state); };
  struct Pair {
    double iou;
    int id_a, id_b;
  };
  std::vector<Pair> pairs;
  for (const TargetRecord& ta : a.targets) {
    if (!visible(ta)) continue;
    for (const TargetRecord& tb : b.targets) {
      if (!visible(tb)) continue;
      const double overlap = (ta.bbox & tb.bbox).area();
      const double united = ta.bbox.area() + tb.bbox.area() - overlap;
      const double iou = united > 0 ? overlap / united : 0.0;
      if (iou >= kTargetMatchIou) pairs.push_back({iou, ta.id, tb.id});
    }
  }
  std::stable_sort(pairs.begin(), pairs.end(),
                   [](const Pair& x, const Pair& y) { return x.iou > y.iou; });
  std::set<int> used_a, used_b;
  std::vector<std::pair<int, int>> matched;
  for (const Pair& pair : pairs) {
    if (used_a.count(pair.id_a) > 0 || used_b.count(pair.id_b) > 0) continue;
    used_a.insert(pair.id_a);
    used_b.insert(pair.id_b);
    matched.emplace_back(pair.id_a, pair.id_b);
  }
  return matched;
}

// The run's saliency map of `frame`: the PFM dump, empty when there is none.
cv::Mat ReadSaliency(const std::string& run, int frame) {
  const std::string path = DumpPath(run, "saliency", frame, "pfm");
  if (!fs::exists(path)) return {};
  return ReadPfmOneChannel(path, "a saliency map");
}

nlohmann::ordered_json OptionalNumber(const std::optional<double>& value) {
  return value ? FiniteOrNull(*value) : nlohmann::ordered_json();
}

nlohmann::ordered_json MetricsJson(const std::optional<SaliencyMetrics>& metrics) {
  if (!metrics) return nullptr;
  return {{"cc", FiniteOrNull(metrics->cc)},
          {"sim", FiniteOrNull(metrics->sim)},
          {"kl", FiniteOrNull(metrics->kl)}};
}

}  // namespace

double CorrelationCoefficient(const cv::Mat& p, const cv::Mat& q) {
  CheckPair(p, q);
  const cv::Mat x = AsDouble(p), y = AsDouble(q);
  cv::Scalar mean_x, std_x, mean_y, std_y;
  cv::meanStdDev(x, mean_x, std_x);
  cv::meanStdDev(y, mean_y, std_y);
  if (std_x[0] == 0.0 || std_y[0] == 0.0) return kNaN;
  const double covariance = cv::mean((x - mean_x[0]).mul(y - mean_y[0]))[0];
  return covariance / (std_x[0] * std_y[0]);
}

double Similarity(const cv::Mat& p, const cv::Mat& q) {
  CheckPair(p, q);
  const cv::Mat x = SumNormalised(p), y = SumNormalised(q);
  if (x.empty() || y.empty()) return kNaN;
  return cv::sum(cv::min(x, y))[0];
}

double KlDivergence(const cv::Mat& p, const cv::Mat& q) {
  CheckPair(p, q);
  const cv::Mat x = SumNormalised(p), y = SumNormalised(q);
  if (x.empty() || y.empty()) return kNaN;
  cv::Mat ratio = y / (x + kSaliencyEpsilon) + kSaliencyEpsilon;
  cv::Mat log_ratio;
  cv::log(ratio, log_ratio);
  return cv::sum(y.mul(log_ratio))[0];
}

SaliencyMetrics CompareSaliency(const cv::Mat& p, const cv::Mat& q) {
  return {CorrelationCoefficient(p, q), Similarity(p, q), KlDivergence(p, q)};
}

FlatConfig FlattenConfigText(const std::string& yaml, const std::string& source) {
  // Read through ParamBlock, which bounds the tree (alias cycles, expansion) and rejects
  // duplicate keys; a run's configuration is input data here, so its errors are input errors.
  FlatConfig flat;
  try {
    flat = FlattenedValues(ParamBlock::Parse(yaml, source));
  } catch (const ConfigError& e) {
    throw InputError(e.what());
  }
  return flat;
}

FlatConfig FlattenConfigFile(const std::string& path) {
  return FlattenConfigText(
      ReadRegularFile(path, "the run's configuration", ExitStatus::kBadInput, kMaxConfigBytes), path);
}

std::vector<ConfigDifference> DiffConfigs(const FlatConfig& a, const FlatConfig& b) {
  std::set<std::string> keys;
  for (const auto& entry : a) keys.insert(entry.first);
  for (const auto& entry : b) keys.insert(entry.first);
  std::vector<ConfigDifference> differences;
  for (const std::string& key : keys) {
    const auto in_a = a.find(key), in_b = b.find(key);
    ConfigDifference difference{key, std::nullopt, std::nullopt};
    if (in_a != a.end()) difference.a = in_a->second;
    if (in_b != b.end()) difference.b = in_b->second;
    if (difference.a && difference.b && SameValue(*difference.a, *difference.b)) continue;
    differences.push_back(difference);
  }
  return differences;
}

std::string DumpPath(const std::string& run, const std::string& kind, int frame,
                     const std::string& extension) {
  char stem[32];
  std::snprintf(stem, sizeof(stem), "%06d.", frame);
  return (fs::path(run) / kind / (stem + extension)).string();
}

RunData LoadRun(const std::string& dir, const std::string& gt) {
  const fs::path run(dir);
  if (!fs::is_directory(run)) throw InputError(dir + ": no such run folder");
  if (!fs::exists(run / "frames.jsonl")) {
    throw InputError(dir + ": not a run folder (no frames.jsonl)");
  }
  RunData data;
  data.dir = dir;
  data.frames = ReadFrameRecords((run / "frames.jsonl").string());
  if (fs::exists(run / "config.yaml"))
    data.config = FlattenConfigFile((run / "config.yaml").string());
  const fs::path summary_path = run / "summary.json";
  if (fs::exists(summary_path)) {
    const std::string text = ReadRegularFile(summary_path.string(), "the run's summary",
                                             ExitStatus::kBadInput, kMaxConfigBytes);
    try {
      const nlohmann::json summary = nlohmann::json::parse(text);
      if (summary.contains("sequence") && summary["sequence"].contains("name")) {
        data.sequence = summary["sequence"]["name"].get<std::string>();
      }
      data.interrupted = summary.value("interrupted", false);
    } catch (const std::exception& e) {
      throw InputError(summary_path.string() + ": not a run summary (" + e.what() + ")");
    }
  }
  const auto folder = data.config.find("sequence.folder");
  if (!gt.empty()) {
    const fs::path objects = fs::path(gt) / "objects.csv";
    std::error_code error;
    if (!fs::is_regular_file(objects, error)) {
      throw InputError(objects.string() + ": no ground-truth objects (--gt " + gt + ")");
    }
    data.ground_truth = objects.string();
    data.attention = EvaluateAttention(data.frames, ReadObjectsCsv(objects.string()));
  } else if (folder != data.config.end() && !folder->second.empty()) {
    const fs::path objects = fs::path(folder->second) / "gt" / "objects.csv";
    const std::optional<KittiSequence> kitti = FindKittiSequence(folder->second);
    std::error_code error;
    if (kitti.has_value() && !kitti->labels.empty()) {
      // A KITTI sequence brings its labels (eval/kitti_truth.h).
      data.ground_truth = kitti->labels;
      data.attention = EvaluateAttention(data.frames, ReadKittiObjects(*kitti));
    } else if (fs::is_regular_file(objects, error)) {
      data.ground_truth = objects.string();
      data.attention = EvaluateAttention(data.frames, ReadObjectsCsv(objects.string()));
    }
  }
  StageTimes totals;
  for (const FrameRecord& record : data.frames) {
    for (const auto& [stage, ms] : record.timings.stages()) totals.Add(stage, ms);
  }
  for (const auto& [stage, ms] : totals.stages()) {
    data.mean_timings_ms.emplace_back(stage, ms / static_cast<double>(data.frames.size()));
  }
  return data;
}

std::vector<TargetSummary> SummariseTargets(const std::vector<FrameRecord>& frames) {
  std::map<int, TargetSummary> by_id;
  for (const FrameRecord& record : frames) {
    for (const TargetRecord& target : record.targets) {
      TargetSummary& summary = by_id[target.id];
      if (summary.frames == 0) {
        summary.id = target.id;
        summary.kind = target.kind;
        summary.first_frame = record.frame;
      }
      summary.last_frame = record.frame;
      ++summary.frames;
    }
  }
  std::vector<TargetSummary> targets;
  for (const auto& entry : by_id) targets.push_back(entry.second);
  std::stable_sort(targets.begin(), targets.end(), [](const auto& x, const auto& y) {
    return x.first_frame != y.first_frame ? x.first_frame < y.first_frame : x.id < y.id;
  });
  for (std::size_t i = 0; i < targets.size(); ++i) targets[i].rank = static_cast<int>(i);
  return targets;
}

namespace {

// How many common frames' saliency maps could not be compared, and why.
struct MapCounts {
  int missing = 0;    // a map is not dumped
  int nonfinite = 0;  // a map has a NaN or infinite pixel
  int undefined = 0;  // a metric is undefined (a constant map)
  int resized = 0;    // the second run's map had another size
};

void AddMapNotes(const MapCounts& counts, int common, const std::string& first_nonfinite,
                 std::vector<std::string>* notes_out) {
  std::vector<std::string>& notes = *notes_out;
  const int missing_maps = counts.missing, nonfinite_maps = counts.nonfinite;
  const int undefined = counts.undefined, resized = counts.resized;
  if (missing_maps > 0) {
    notes.push_back(
        std::to_string(missing_maps) + " of " + std::to_string(common) +
        " common frames lack a saliency map (RUN/saliency/NNNNNN.pfm) in one run: their "
        "saliency metrics are omitted (dump them with --set 'output.dump=[saliency,overlay]')");
  }
  if (nonfinite_maps > 0) {
    notes.push_back(
        std::to_string(nonfinite_maps) + " of " + std::to_string(common) +
        " common frames have a saliency map with NaN or infinite pixels (the first: " +
        first_nonfinite + "): their saliency metrics are omitted from the means");
  }
  if (undefined > 0) {
    notes.push_back(
        std::to_string(undefined) + " of " + std::to_string(common) +
        " common frames have a metric that is undefined (a constant or all-zero map: CC needs "
        "variation, SIM and KL a positive sum); it is omitted from that metric's mean");
  }
  if (resized > 0) {
    notes.push_back(std::to_string(resized) +
                               " saliency maps of the second run were resized to the size of "
                               "the first run's");
  }
}

// The frames both runs have, by index: their targets, matched pairs and saliency metrics,
// with notes on what could not be compared. `pair_frames`: the frames each (A id, B id) pair
// was matched in.
void CompareFrames(const RunData& a, const RunData& b, RunComparison* comparison_out,
                   std::map<std::pair<int, int>, int>* pair_frames_out) {
  RunComparison& comparison = *comparison_out;
  std::map<std::pair<int, int>, int>& pair_frames = *pair_frames_out;
  std::map<int, const FrameRecord*> frames_b;
  for (const FrameRecord& record : b.frames) frames_b[record.frame] = &record;
  int missing_maps = 0, resized = 0, nonfinite_maps = 0, undefined = 0;
  std::string first_nonfinite;  // the first map with a NaN or infinite pixel
  double sums[3] = {0, 0, 0};
  int counts[3] = {0, 0, 0};
  for (const FrameRecord& record_a : a.frames) {
    const auto found = frames_b.find(record_a.frame);
    if (found == frames_b.end()) continue;
    const FrameRecord& record_b = *found->second;
    FrameComparison frame;
    frame.frame = record_a.frame;
    frame.targets_a = VisibleTargets(record_a);
    frame.targets_b = VisibleTargets(record_b);
    const auto matched = MatchFrame(record_a, record_b);
    frame.matched = static_cast<int>(matched.size());
    for (const auto& pair : matched) ++pair_frames[pair];

    const cv::Mat p = ReadSaliency(a.dir, record_a.frame);
    cv::Mat q = ReadSaliency(b.dir, record_b.frame);
    const auto finite = [&](const cv::Mat& map, const RunData& run, int frame) {
      if (cv::checkRange(map)) return true;
      if (first_nonfinite.empty()) first_nonfinite = DumpPath(run.dir, "saliency", frame, "pfm");
      return false;
    };
    if (p.empty() || q.empty() || p.channels() != 1 || q.channels() != 1) {
      ++missing_maps;
    } else if (!finite(p, a, record_a.frame) | !finite(q, b, record_b.frame)) {
      ++nonfinite_maps;
    } else {
      if (q.size() != p.size()) {
        cv::resize(q, q, p.size(), 0, 0, cv::INTER_AREA);
        ++resized;
      }
      frame.saliency = CompareSaliency(p, q);
      const double values[3] = {frame.saliency->cc, frame.saliency->sim, frame.saliency->kl};
      bool all = true;
      for (int i = 0; i < 3; ++i) {
        if (std::isfinite(values[i])) {
          sums[i] += values[i], ++counts[i];
        } else {
          all = false;
        }
      }
      undefined += all ? 0 : 1;
    }
    comparison.frames.push_back(frame);
  }
  const int common = static_cast<int>(comparison.frames.size());
  if (common != comparison.frames_a || common != comparison.frames_b) {
    comparison.notes.push_back("the runs have " + std::to_string(comparison.frames_a) + " and " +
                               std::to_string(comparison.frames_b) + " frames; the " +
                               std::to_string(common) + " common frames are compared");
  }
  AddMapNotes({missing_maps, nonfinite_maps, undefined, resized}, common, first_nonfinite,
              &comparison.notes);
  if (counts[0] + counts[1] + counts[2] > 0) {
    const auto mean = [&](int i) { return counts[i] > 0 ? sums[i] / counts[i] : kNaN; };
    comparison.mean_saliency = SaliencyMetrics{mean(0), mean(1), mean(2)};
  }
}

// Targets: each of A with the one of B it was paired with most often, one to one.
void MatchTargets(const RunData& a, const RunData& b,
                  const std::map<std::pair<int, int>, int>& pair_frames,
                  RunComparison* comparison_out) {
  RunComparison& comparison = *comparison_out;
  comparison.targets_a = SummariseTargets(a.frames);
  comparison.targets_b = SummariseTargets(b.frames);
  std::vector<std::pair<std::pair<int, int>, int>> pairs(pair_frames.begin(), pair_frames.end());
  std::stable_sort(pairs.begin(), pairs.end(),
                   [](const auto& x, const auto& y) { return x.second > y.second; });
  std::map<int, TargetMatch> match_of_a;
  std::set<int> used_b;
  for (const auto& [ids, frames] : pairs) {
    if (match_of_a.count(ids.first) > 0 || used_b.count(ids.second) > 0) continue;
    match_of_a[ids.first] = {ids.first, ids.second, frames};
    used_b.insert(ids.second);
  }
  std::map<int, int> rank_b;
  for (const TargetSummary& target : comparison.targets_b) rank_b[target.id] = target.rank;
  int previous_rank_b = -1;
  for (const TargetSummary& target : comparison.targets_a) {
    const auto found = match_of_a.find(target.id);
    if (found == match_of_a.end()) continue;
    comparison.matches.push_back(found->second);
    const int rank = rank_b[found->second.id_b];
    if (rank < previous_rank_b) comparison.same_order = false;
    previous_rank_b = rank;
  }
  for (const TargetSummary& target : comparison.targets_a) {
    if (match_of_a.count(target.id) == 0) comparison.matches.push_back({target.id, -1, 0});
  }
  for (const TargetSummary& target : comparison.targets_b) {
    if (used_b.count(target.id) == 0) comparison.matches.push_back({-1, target.id, 0});
  }
}

// Timings: the stages of A in order, then those only in B.
void CompareTimings(const RunData& a, const RunData& b, RunComparison* comparison) {
  for (const auto& [stage, ms] : a.mean_timings_ms) comparison->timings.push_back({stage, ms, {}});
  for (const auto& [stage, ms] : b.mean_timings_ms) {
    // The binding is captured through a reference of its own: clang before 16 cannot capture
    // a structured binding (C++20 P1091R3), and the fuzz build uses clang 14.
    const auto found =
        std::find_if(comparison->timings.begin(), comparison->timings.end(),
                     [&stage = stage](const StageTiming& t) { return t.stage == stage; });
    if (found != comparison->timings.end()) {
      found->b = ms;
    } else {
      comparison->timings.push_back({stage, {}, ms});
    }
  }
}

}  // namespace

RunComparison CompareRuns(const RunData& a, const RunData& b) {
  RunComparison comparison;
  comparison.run_a = a.dir;
  comparison.run_b = b.dir;
  comparison.frames_a = static_cast<int>(a.frames.size());
  comparison.frames_b = static_cast<int>(b.frames.size());
  comparison.config = DiffConfigs(a.config, b.config);
  if (!a.sequence.empty() && !b.sequence.empty() && a.sequence != b.sequence) {
    comparison.notes.push_back("the runs are of different sequences (" + a.sequence + ", " +
                               b.sequence + "): frames are compared by index");
  }
  if (a.interrupted) comparison.notes.push_back(a.dir + " was interrupted");
  if (b.interrupted) comparison.notes.push_back(b.dir + " was interrupted");

  std::map<std::pair<int, int>, int> pair_frames;
  CompareFrames(a, b, &comparison, &pair_frames);
  MatchTargets(a, b, pair_frames, &comparison);
  CompareTimings(a, b, &comparison);
  std::vector<std::pair<int, int>> matched;
  for (const TargetMatch& m : comparison.matches) {
    if (m.id_a >= 0 && m.id_b >= 0) matched.emplace_back(m.id_a, m.id_b);
  }
  comparison.depth = CompareDepth(a.frames, b.frames, matched);
  return comparison;
}

nlohmann::ordered_json TargetsToJson(const std::vector<TargetSummary>& targets) {
  nlohmann::ordered_json out = nlohmann::ordered_json::array();
  for (const TargetSummary& t : targets) {
    out.push_back({{"id", t.id},
                   {"kind", t.kind},
                   {"first_frame", t.first_frame},
                   {"last_frame", t.last_frame},
                   {"frames", t.frames},
                   {"rank", t.rank}});
  }
  return out;
}

nlohmann::ordered_json AttentionToJson(const std::optional<AttentionScores>& scores) {
  if (!scores) return nullptr;
  return {{"frames", scores->frames},
          {"objects", scores->objects},
          {"attended", scores->attended},
          {"coverage", scores->coverage},
          {"mean_latency", scores->mean_latency},
          {"revisits", scores->revisits},
          {"identity_switches", scores->identity_switches},
          {"mean_iou", scores->mean_iou}};
}

nlohmann::ordered_json ComparisonToJson(const RunComparison& c) {
  const auto optional_text = [](const std::optional<std::string>& value) {
    return value ? nlohmann::ordered_json(*value) : nlohmann::ordered_json();
  };
  nlohmann::ordered_json config = nlohmann::ordered_json::array();
  for (const ConfigDifference& d : c.config) {
    config.push_back({{"key", d.key}, {"a", optional_text(d.a)}, {"b", optional_text(d.b)}});
  }
  nlohmann::ordered_json frames = nlohmann::ordered_json::array();
  for (const FrameComparison& f : c.frames) {
    nlohmann::ordered_json frame = {{"frame", f.frame}};
    frame.update(MetricsJson(f.saliency).is_null()
                     ? nlohmann::ordered_json{{"cc", nullptr}, {"sim", nullptr}, {"kl", nullptr}}
                     : MetricsJson(f.saliency));
    frame["targets_a"] = f.targets_a;
    frame["targets_b"] = f.targets_b;
    frame["matched"] = f.matched;
    frames.push_back(frame);
  }
  nlohmann::ordered_json matched = nlohmann::ordered_json::array();
  nlohmann::ordered_json only_a = nlohmann::ordered_json::array();
  nlohmann::ordered_json only_b = nlohmann::ordered_json::array();
  for (const TargetMatch& m : c.matches) {
    if (m.id_a >= 0 && m.id_b >= 0) {
      matched.push_back({{"a", m.id_a}, {"b", m.id_b}, {"frames", m.frames_matched}});
    } else if (m.id_a >= 0) {
      only_a.push_back(m.id_a);
    } else {
      only_b.push_back(m.id_b);
    }
  }
  nlohmann::ordered_json order_a = nlohmann::ordered_json::array();
  nlohmann::ordered_json order_b = nlohmann::ordered_json::array();
  for (const TargetSummary& t : c.targets_a) order_a.push_back(t.id);
  for (const TargetSummary& t : c.targets_b) order_b.push_back(t.id);
  nlohmann::ordered_json timings = nlohmann::ordered_json::array();
  for (const StageTiming& t : c.timings) {
    timings.push_back({{"stage", t.stage}, {"a", OptionalNumber(t.a)}, {"b", OptionalNumber(t.b)}});
  }
  return {{"a", c.run_a},
          {"b", c.run_b},
          {"frames_a", c.frames_a},
          {"frames_b", c.frames_b},
          {"common_frames", c.frames.size()},
          {"config_differences", config},
          {"saliency_mean", MetricsJson(c.mean_saliency)},
          {"targets",
           {{"matched", matched},
            {"only_a", only_a},
            {"only_b", only_b},
            {"order_a", order_a},
            {"order_b", order_b},
            {"same_order", c.same_order},
            {"a", TargetsToJson(c.targets_a)},
            {"b", TargetsToJson(c.targets_b)}}},
          {"timings_ms", timings},
          {"depth", DepthComparisonToJson(c.depth)},
          {"frames", frames},
          {"notes", c.notes}};
}

}  // namespace attend
