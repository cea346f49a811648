// What `attend eval-scanpaths` compares (app/evaluate_scanpaths.h), read and checked: each
// image's observers' fixation sequences, and each map folder's scanpath.json.
#pragma once

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "eval/fixation_data.h"
#include "eval/scanpath_metrics.h"

namespace attend {

// How the observers' sequences are cut (docs/FIXATIONS.md, "Scanpaths").
struct ObserverReading {
  int length = 8;           // the first `length` fixations are compared
  bool drop_first = true;   // each observer's first recorded fixation left out first
  DurationColumn durations{DurationColumn::Source::kHeader};
};

// One image's observers, as they are compared.
struct ObservedImage {
  std::string id;
  cv::Size size;  // the stimulus's
  // Per observer (subjects ascending): the fixations inside the image, after the first is
  // dropped, cut to `length`. Observers left with none are not here.
  std::vector<Scanpath> observers;
  // The durations of every fixation kept before the cut (for the median the models get);
  // empty when the file gives none.
  std::vector<double> durations_s;
  int observers_left_out = 0;  // with no fixation left
  int fixations_outside = 0;   // outside the image, left out
};

// Reads the stimulus's size and the fixation file. InputError naming the file (and line).
ObservedImage ReadObservedImage(const FixationItem& item, const ObserverReading& reading);

// A map folder and its scanpath.json.
struct ModelScanpaths {
  std::string name;    // NAME of NAME=FOLDER, or the folder's name
  std::string folder;
  std::string file;    // FOLDER/scanpath.json
  nlohmann::json paths;  // {"<id>": [{"x", "y", ...}, ...], ...}
};

// Parses "[NAME=]FOLDER" and reads FOLDER/scanpath.json. InputError when the folder or the file
// is missing (saying how to write it) or the file is not a JSON object.
ModelScanpaths ReadModelScanpaths(const std::string& spec);

// The first `length` regions of image `id` in `model`, each lasting its "duration_s" when the
// file gives one, else `duration_s`. InputError naming the file and the image when the image is
// missing, its scanpath empty (unless `allow_empty`: then an empty scanpath) or a region
// without numeric "x" and "y".
Scanpath ModelScanpath(const ModelScanpaths& model, const std::string& id, int length,
                       double duration_s, bool allow_empty);

}  // namespace attend
