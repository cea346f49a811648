#include "app/score_tracks.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <system_error>
#include <vector>

#include "eval/tracking_scores.h"
#include "io/ground_truth.h"
#include "io/tracking_files.h"
#include "util/error.h"
#include "util/strings.h"

namespace attend {

namespace {

namespace fs = std::filesystem;

// The ground truth indexed by frame (empty boxes where there is none), and how it was read.
struct GroundTruth {
  std::vector<cv::Rect2d> boxes;
  std::string format;
  std::optional<int> id;
};

bool IsObjectsCsv(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    const size_t begin = line.find_first_not_of(" \t\r");
    if (begin == std::string::npos) continue;
    return line.compare(begin, 6, "frame,") == 0;
  }
  return false;
}

GroundTruth ReadGroundTruth(const ScoreTracksRequest& request) {
  std::error_code error;
  if (!fs::is_regular_file(request.gt, error)) throw InputError(request.gt + ": no such file");
  GroundTruth truth;
  if (!IsObjectsCsv(request.gt)) {
    if (request.gt_id) {
      throw ConfigError("--gt-id " + std::to_string(*request.gt_id) + ": " + request.gt +
                        " is an OTB box list of one object; --gt-id picks an object of an "
                        "`attend synth` gt/objects.csv");
    }
    truth.format = "otb";
    truth.boxes = ReadOtbGroundTruth(request.gt);
    return truth;
  }
  truth.format = "objects.csv";
  const std::vector<GtObject> objects = ReadObjectsCsv(request.gt);
  std::set<int> ids;
  for (const GtObject& object : objects) ids.insert(object.id);
  std::vector<std::string> id_texts;
  for (const int id : ids) id_texts.push_back(std::to_string(id));
  if (!request.gt_id) {
    if (ids.size() != 1) {
      throw ConfigError(request.gt + " holds objects " + Join(id_texts, ", ") +
                        "; choose the one to score against with --gt-id");
    }
    truth.id = *ids.begin();
  } else {
    if (ids.count(*request.gt_id) == 0) {
      throw ConfigError("--gt-id " + std::to_string(*request.gt_id) + ": " + request.gt +
                        " has no such object (it holds " +
                        (ids.empty() ? std::string("none") : Join(id_texts, ", ")) + ")");
    }
    truth.id = *request.gt_id;
  }
  for (const GtObject& object : objects) {
    if (object.id != *truth.id) continue;
    if (object.frame >= static_cast<int>(truth.boxes.size())) truth.boxes.resize(object.frame + 1);
    truth.boxes[object.frame] = object.box;  // empty while hidden
  }
  return truth;
}

}  // namespace

nlohmann::json ScoreTracks(const ScoreTracksRequest& request) {
  const bool has_range = request.has_range;
  const std::vector<TrackRow> rows = ReadTracksCsv(request.tracks);
  if (rows.empty()) throw InputError(request.tracks + ": no rows; nothing to score");
  const GroundTruth truth = ReadGroundTruth(request);

  // Each target's boxes by frame, whatever its state: a target not found keeps its last known
  // box, as the OTB toolkit carries a tracker's last result over the frames it fails in.
  std::map<int, std::vector<cv::Rect2d>> predicted;
  std::map<int, int> first_frame, rows_of, found_of;
  std::set<std::pair<int, int>> seen;  // (id, frame)
  for (const TrackRow& row : rows) {
    if (!seen.emplace(row.id, row.frame).second) {
      throw InputError(request.tracks + ": target " + std::to_string(row.id) +
                       " has two rows for frame " + std::to_string(row.frame));
    }
    std::vector<cv::Rect2d>& boxes = predicted[row.id];
    if (row.frame >= static_cast<int>(boxes.size())) boxes.resize(row.frame + 1);
    boxes[row.frame] = row.box;
    const auto [it, inserted] = first_frame.emplace(row.id, row.frame);
    if (!inserted) it->second = std::min(it->second, row.frame);
    ++rows_of[row.id];
    if (row.state == "found") ++found_of[row.id];
  }
  std::vector<int> ids;
  if (request.id) {
    if (!predicted.count(*request.id)) {
      std::vector<std::string> present;
      for (const auto& [id, boxes] : predicted) present.push_back(std::to_string(id));
      throw ConfigError("--id " + std::to_string(*request.id) + ": " + request.tracks +
                        " has no such target (it holds " + Join(present, ", ") + ")");
    }
    ids.push_back(*request.id);
  } else {
    for (const auto& [id, boxes] : predicted) ids.push_back(id);
  }

  nlohmann::json targets = nlohmann::json::array();
  const int truth_last = static_cast<int>(truth.boxes.size()) - 1;
  for (const int id : ids) {
    // From the target's first frame (or FIRST) to the end of the ground truth (or LAST).
    const int first = has_range ? request.first_frame : first_frame[id];
    const int last =
        request.last_frame >= 0 ? std::min(request.last_frame, truth_last) : truth_last;
    std::vector<cv::Rect2d> scored = truth.boxes;
    for (int f = 0; f < static_cast<int>(scored.size()); ++f) {
      if (f < first || f > last) scored[f] = cv::Rect2d();
    }
    const TrackingScores scores = ScoreTracking(predicted[id], scored);
    targets.push_back({{"id", id},
                       {"first_frame", first},
                       {"last_frame", last},
                       {"frames", scores.frames},
                       {"rows", rows_of[id]},
                       {"found", found_of[id]},
                       {"success_auc", scores.success_auc},
                       {"precision_20", scores.precision_20},
                       {"mean_iou", scores.mean_iou},
                       {"success", scores.success},
                       {"precision", scores.precision}});
  }
  const nlohmann::json report = {{"tracks", request.tracks},
                                 {"gt", request.gt},
                                 {"gt_format", truth.format},
                                 {"gt_id", truth.id ? nlohmann::json(*truth.id) : nullptr},
                                 {"targets", targets}};
  return report;
}

}  // namespace attend
