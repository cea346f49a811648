// Comparing attention runs (SPEC 3.2 `attend compare`, SPEC 4): configuration differences,
// saliency map metrics per frame, targets matched between runs, attention order and timings.
//
// The saliency metrics follow the MIT saliency benchmark (Bylinskii, Judd, Oliva, Torralba and
// Durand, "What do different evaluation metrics tell us about saliency models?", 2016,
// arXiv:1604.03605), with P the map of the reference run (the first one named) and Q the map
// of the run compared with it:
//   CC   Pearson's correlation coefficient of P and Q over all pixels,
//        cov(P, Q) / (sigma(P) sigma(Q)); 1 for identical maps, undefined (NaN) when either
//        map is constant.
//   SIM  similarity (histogram intersection): sum_i min(P_i, Q_i) with P and Q each divided
//        by its sum; 1 for identical maps, 0 for disjoint ones.
//   KL   Kullback-Leibler divergence of Q from P: sum_i Q_i log(eps + Q_i / (P_i + eps)) with P
//        and Q each divided by its sum and eps = 2.2204e-16 (the benchmark's); 0 for identical
//        maps, larger is more different. Not symmetric.
// SIM and KL are undefined (NaN) when a map sums to zero. NaN metrics are written as null and
// left out of means.
//
// Targets are matched frame by frame: every target of run A that is new, tracked or resumed in
// a frame with every such target of run B, pairs with box IoU >= 0.5 taken greedily by
// decreasing IoU, one to one. Over the run, a target of A is matched with the target of B it was paired with
// most often (again greedily, one to one); the others are only in one run.
#pragma once

#include <map>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "eval/run_depth.h"
#include "eval/run_evaluation.h"
#include "io/frame_record.h"

namespace attend {

// eps of the MIT saliency benchmark's KL divergence (Matlab's eps).
inline constexpr double kSaliencyEpsilon = 2.2204e-16;
// Box IoU from which two targets of two runs are the same object.
inline constexpr double kTargetMatchIou = 0.5;

struct SaliencyMetrics {
  double cc = 0.0;
  double sim = 0.0;
  double kl = 0.0;
};

// The definitions above; `p` and `q` are one-channel float maps of one size (checked).
double CorrelationCoefficient(const cv::Mat& p, const cv::Mat& q);
double Similarity(const cv::Mat& p, const cv::Mat& q);
double KlDivergence(const cv::Mat& p, const cv::Mat& q);
SaliencyMetrics CompareSaliency(const cv::Mat& p, const cv::Mat& q);

// A YAML document flattened into dotted keys and scalar values: maps give "a.b", a sequence
// of maps that all have a scalar `name` gives "a.<name>.key" (so features.skin.weight), a
// sequence of scalars is one value "[x, y]", any other sequence "a.0", "a.1", ...
using FlatConfig = std::map<std::string, std::string>;
// Throws InputError naming the file when it cannot be read or parsed.
FlatConfig FlattenConfigFile(const std::string& path);
FlatConfig FlattenConfigText(const std::string& yaml, const std::string& source = "<config>");

struct ConfigDifference {
  std::string key;
  std::optional<std::string> a;  // absent: the key is only in the other run
  std::optional<std::string> b;
};

// The keys whose values differ or that exist in one run only, in key order. Two values that
// both read as numbers are compared as numbers (1 and 1.0 are equal).
std::vector<ConfigDifference> DiffConfigs(const FlatConfig& a, const FlatConfig& b);

// What a run folder (SPEC 3.3) holds that a comparison needs.
struct RunData {
  std::string dir;
  std::string sequence;  // summary.json sequence.name, "" when unknown
  FlatConfig config;     // config.yaml, flattened
  std::vector<FrameRecord> frames;
  std::vector<std::pair<std::string, double>> mean_timings_ms;  // per stage, over the frames
  bool interrupted = false;
  // `attend eval`'s scores (SPEC 4) when the run's sequence folder has gt/objects.csv.
  std::optional<AttentionScores> attention;
  std::string ground_truth;  // the objects.csv they were scored against
};

// Reads RUN/frames.jsonl, RUN/config.yaml and RUN/summary.json (the last optional), and scores
// the run against ground truth: `gt`'s objects.csv when a gt/ folder is given (a run whose
// source has none, such as a video), else its sequence.folder's gt/objects.csv when there is
// one. A folder without frames.jsonl, or a given `gt` without objects.csv, is an InputError
// naming it.
RunData LoadRun(const std::string& dir, const std::string& gt = "");

// RUN/<kind>/NNNNNN.<extension>, the dump of one frame.
std::string DumpPath(const std::string& run, const std::string& kind, int frame,
                     const std::string& extension);

// A target of one run: when it was first attended and where it ranks in the attention order.
struct TargetSummary {
  int id = 0;
  std::string kind;
  int first_frame = -1;  // frame of its first attention
  int last_frame = -1;
  int frames = 0;  // frames it appears in
  int rank = 0;    // 0-based position in the attention order of its run
};

struct TargetMatch {
  int id_a = -1;  // -1: only in run B
  int id_b = -1;  // -1: only in run A
  int frames_matched = 0;
};

struct FrameComparison {
  int frame = 0;
  std::optional<SaliencyMetrics> saliency;  // none when a map is missing
  int targets_a = 0;
  int targets_b = 0;
  int matched = 0;
};

struct StageTiming {
  std::string stage;
  std::optional<double> a;  // mean ms a frame
  std::optional<double> b;
};

struct RunComparison {
  std::string run_a;
  std::string run_b;
  std::vector<ConfigDifference> config;
  std::vector<FrameComparison> frames;  // the common frames, in order
  int frames_a = 0;
  int frames_b = 0;
  std::optional<SaliencyMetrics> mean_saliency;  // over the frames with both maps
  std::vector<TargetSummary> targets_a;          // in attention order
  std::vector<TargetSummary> targets_b;
  std::vector<TargetMatch> matches;  // matched pairs first (by A's order), then the unmatched
  bool same_order = true;            // matched targets first attended in the same order
  std::vector<StageTiming> timings;
  // The targets' depth (eval/run_depth.h): none when neither run has one.
  std::optional<DepthComparison> depth;
  std::vector<std::string> notes;  // what could not be compared, and why
};

// The targets of a run in attention order (by first frame, then id).
std::vector<TargetSummary> SummariseTargets(const std::vector<FrameRecord>& frames);

// Compares run `b` with the reference run `a`, reading the saliency dumps of both folders.
RunComparison CompareRuns(const RunData& a, const RunData& b);

nlohmann::ordered_json ComparisonToJson(const RunComparison& comparison);
nlohmann::ordered_json TargetsToJson(const std::vector<TargetSummary>& targets);
// The scores as `attend eval` prints them, without the per-object list; null without them.
nlohmann::ordered_json AttentionToJson(const std::optional<AttentionScores>& scores);

}  // namespace attend
