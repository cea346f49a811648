// The controller of `attend eval-scanpaths` (docs/FIXATIONS.md, "Scanpaths"): the order of
// attention in each MAPS/scanpath.json compared with every observer's fixation sequence of a
// dataset by ScanMatch, the sequence score and MultiMatch (eval/scanpath_metrics.h), beside
// the human ceiling, scanpaths drawn around the centre and each map's peaks, in one run on the
// same images. The command only parses its arguments.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "eval/fixation_data.h"
#include "eval/scanpath_metrics.h"

namespace attend {

struct EvalScanpathsRequest {
  std::vector<std::string> maps;       // [NAME=]FOLDER, each with scanpath.json
  std::string dataset;
  std::string out;                     // "": no files
  std::vector<std::string> baselines;  // of ScanpathBaselineNames()
  int skip = 0;   // leave out the first N items (by id)
  int first = 0;  // then score only the first N items; 0: all
  // The first `length` fixations of every scanpath are compared (a model's, an observer's).
  int length = 8;
  // Leave out each observer's first recorded fixation, which the fixation cross before the
  // image decides, not the image.
  bool drop_first = true;
  DurationColumn durations{DurationColumn::Source::kHeader};
  ScanMatchOptions scanmatch;  // grid, gap, temporal bins; the threshold is the next field
  double scanmatch_threshold = 0.0;  // cells; 0: 2 sd of the observers' saccade amplitudes
  MultiMatchOptions multimatch;
  int centre_draws = 10;          // centre-bias scanpaths drawn per image, scores averaged
  uint64_t seed = 1;              // of the centre draws
  double peak_separation = 0.05;  // share of the map's larger side (SaliencyPeaks)
  // An image whose scanpath.json lists no region: an InputError (false), or 0 in every
  // measure for that model (true: a model that attends nothing there predicts nothing).
  bool empty_scores_zero = false;
  std::string command_line;
};

// "human", "centre", "peaks".
const std::vector<std::string>& ScanpathBaselineNames();

// {"scanmatch", "sequence", "mm_shape", "mm_direction", "mm_length", "mm_position",
// "mm_duration"}: the CSV columns and the JSON keys, in order.
const std::vector<std::string>& ScanpathMeasureNames();

struct ScanpathEvaluationObserver {
  std::function<void(const std::string& note)> on_note;
  std::function<void(int done, int total)> on_progress;
};

struct ScanpathEvaluation {
  std::string table;  // a Markdown table: each method's means with 95 % intervals
  double threshold_cells = 0.0;    // the ScanMatch threshold used
  double model_duration_s = -1.0;  // the duration given to attend's and the baselines' fixations
  int images = 0;                  // images scored
};

// ConfigError for bad options (unknown baselines, nothing to score, temporal bins without
// durations); InputError naming the file (and line or image) for a dataset, scanpath.json or
// map that cannot be read or lacks an image, and for an empty scanpath; OutputError when --out
// cannot be written.
ScanpathEvaluation EvaluateScanpaths(const EvalScanpathsRequest& request,
                                     const ScanpathEvaluationObserver& observer);

}  // namespace attend
