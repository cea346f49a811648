// The controller of `attend eval-tracking` (SPEC 3.2, 4; docs/TRACKING.md): the OTB one-pass
// scores of a tracks.csv, as `attend track` writes it, against OTB ground truth or a
// sequence's gt/objects.csv. The command only parses its arguments and prints the report.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>

namespace attend {

struct ScoreTracksRequest {
  std::string tracks;        // a tracks.csv
  std::string gt;            // an OTB box list or a gt/objects.csv
  std::optional<int> id;     // score this target only (--id)
  std::optional<int> gt_id;  // the object of an objects.csv (--gt-id)
  bool has_range = false;    // score frames first_frame..last_frame only
  int first_frame = 0;
  int last_frame = -1;  // -1: to the end of the ground truth
};

// The report attend eval-tracking prints: per target its frames, rows, success AUC, precision
// at 20 px, mean IoU and success curve. InputError for unreadable or inconsistent files;
// ConfigError for a target or object that is not there or must be chosen.
nlohmann::json ScoreTracks(const ScoreTracksRequest& request);

}  // namespace attend
