// The controller of `attend eval-fixations` (docs/FIXATIONS.md): saliency map folders
// and baselines scored against human eye fixations (NSS, AUC-Judd, shuffled AUC, CC, SIM, KL,
// and the share of fixations in the first attended regions when a folder has scanpath.json),
// with per-image CSVs and fixations.json on request. The command only parses its arguments.
#pragma once

#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace attend {

// The depth of the scanpath shares: the first 1..5 attended regions.
constexpr int kScanpathDepth = 5;

struct EvalFixationsRequest {
  std::vector<std::string> maps;  // [NAME=]FOLDER
  std::string dataset;
  std::string out;
  std::vector<std::string> baselines;
  double baseline_blur = 0.03;
  double sigma = 0.0;  // px at the scored size; 0: 0.025 x the larger side
  int max_side = 640;
  int skip = 0;   // leave out the first N items (by id)
  int first = 0;  // then score only the first N items; 0: all
  bool quiet = false;
  std::string command_line;
};

// What a scoring run tells as it goes: a stimulus that cannot be read (the others are still
// scored), a map resized to its stimulus, and every 50 images scored.
struct FixationEvaluationObserver {
  std::function<void(const std::string& error)> on_unreadable;
  std::function<void(const std::string& note)> on_note;
  std::function<void(int done, int total)> on_progress;
};

struct FixationEvaluation {
  std::string table;                // a Markdown table: each method's means with 95 % intervals
  std::vector<std::string> failed;  // stimuli that could not be read
  // For each folder with scanpath.json: the mean share of fixations in the first k regions.
  std::vector<std::pair<std::string, std::vector<double>>> scanpath_shares;
};

// ConfigError for unknown baselines or nothing to score; InputError for a dataset, folder or
// map that cannot be read, or an output that cannot be written.
FixationEvaluation EvaluateFixations(const EvalFixationsRequest& request,
                                     const FixationEvaluationObserver& observer);

}  // namespace attend
