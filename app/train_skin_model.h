// The controller of `attend skin-train` (SPEC 2.3, 3.2; docs/SKIN.md): fits the TSL skin colour
// model to labelled data, chooses its threshold, measures it on a held-out split and writes
// the model file. The command only parses its arguments and prints the report.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "features/skin_training.h"

namespace attend {

struct SkinTrainRequest {
  std::vector<std::string> data;  // items io/skin_files.h ReadSkinData reads
  std::string out;                // the model file
  ThresholdRule rule;
  double holdout = 0.2;      // share of the samples held out, [0, 1)
  uint64_t seed = 1;         // of the split
  bool overwrite = false;    // replace an existing model file
  std::string command_line;  // recorded in the model's provenance
};

// Returns the report attend skin-train prints: samples, mean, covariance, threshold, rule,
// the training and held-out rates and the time taken. OutputError when `out` is a folder or
// exists without `overwrite`, or cannot be written; InputError for bad data or data without
// skin samples. Nothing is written unless the model is made.
nlohmann::json TrainSkinModel(const SkinTrainRequest& request);

}  // namespace attend
