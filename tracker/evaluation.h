// Tracking results as files and their scores (SPEC 3.2, 4): tracks.csv, OTB ground truth, and
// the OTB one-pass evaluation (success AUC over IoU thresholds 0:0.05:1, precision at 20 px).
#pragma once

#include <map>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace attend {

// One row of tracks.csv: frame,id,x,y,w,h,state.
struct TrackRow {
  int frame = 0;
  int id = 0;
  cv::Rect2d box;
  std::string state;  // found, occluded or lost
};

// tracks.csv with its header. InputError naming the file and line of a malformed row.
std::vector<TrackRow> ReadTracksCsv(const std::string& path);
// Writes tracks.csv (OutputError when it cannot).
void WriteTracksCsv(const std::string& path, const std::vector<TrackRow>& rows);

// An OTB groundtruth_rect.txt: one box a line, "x y w h" separated by tabs, spaces or commas,
// 1-based pixel coordinates (converted here to 0-based). Frame i of the file is line i + 1.
std::vector<cv::Rect2d> ReadOtbGroundTruth(const std::string& path);

struct TrackingScores {
  int frames = 0;                   // frames with a ground-truth box
  double success_auc = 0.0;         // mean over thresholds 0, 0.05, ..., 1 of success rate
  double precision_20 = 0.0;        // share of frames with centre error <= 20 px
  std::vector<double> success;      // success rate per threshold (21 values)
  double mean_iou = 0.0;
};

// Scores a sequence of predicted boxes against ground truth, frame by frame (both indexed by
// frame). A frame without a prediction (or an empty one: not found) has IoU 0 and an infinite
// centre error; frames whose ground truth is empty (object not visible) are skipped.
TrackingScores ScoreTracking(const std::vector<cv::Rect2d>& predicted,
                             const std::vector<cv::Rect2d>& truth);

}  // namespace attend
