// The controller of `attend fit-weights` (docs/FIXATIONS.md): feature weights fitted
// to eye fixations on the first images of a dataset, written as a whole configuration. The
// command only parses its arguments.
#pragma once

#include <string>
#include <vector>

#include "eval/weight_fit.h"
#include "pipeline/attend_options.h"

namespace attend {

struct FitWeightsRequest {
  std::string dataset;      // a fixation dataset folder (eval/fixation_data.h)
  AttendOptions options;    // whose enabled features are weighed
  std::string config_path;  // where `options` came from, for messages and the header
  std::string home;         // the attend home (plugins' relative data paths)
  int train = 100;          // the first images by id
  double step = 0.1;        // of the weight grid
  int max_side = 128;       // maps and fixations are scaled to at most this side
  std::string out;          // the configuration to write
};

struct FitWeightsResult {
  std::vector<std::string> features;  // the weighed features, in list order
  WeightFit fit;                      // their weights, the candidates tried, the training NSS
  int images = 0;                     // images used for fitting (1..images by id)
};

// ConfigError when there is no enabled feature or more than 8; InputError for a dataset or
// image that cannot be read, or an output that cannot be written.
FitWeightsResult FitFeatureWeights(const FitWeightsRequest& request);

}  // namespace attend
