// Tracking results as files and their scores (SPEC 3.2, 4): tracks.csv, OTB ground truth, and
// the OTB one-pass evaluation (success AUC over IoU thresholds 0:0.05:1, precision at 20 px) of
// Wu, Lim and Yang, "Online Object Tracking: A Benchmark", CVPR 2013. docs/TRACKING.md has the
// formats and the definitions with worked examples.
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

// tracks.csv: the header line "frame,id,x,y,w,h,state", then one row a target and frame; x, y,
// w, h in 0-based pixels of the frame (x, y the top-left corner), state found, occluded or lost.
// Blank lines are ignored. A missing header, a row without 7 fields, a field that is not a
// number, a non-integer frame or id, a negative frame, id, w or h, or another state: InputError
// naming the file and line.
std::vector<TrackRow> ReadTracksCsv(const std::string& path);
// Writes tracks.csv with its header, numbers in full precision (round trip through
// ReadTracksCsv is exact). OutputError when it cannot.
void WriteTracksCsv(const std::string& path, const std::vector<TrackRow>& rows);

// An OTB groundtruth_rect.txt: one box a line, "x y w h" separated by any run of tabs, spaces
// and commas, 1-based pixel coordinates (converted here to 0-based: x - 1, y - 1). Frame i of the
// file is line i + 1. A box with w or h 0, or with a NaN field, is "no ground truth" and comes
// back empty (Rect2d()). Trailing blank lines are ignored; a blank line before the last box, a
// line without 4 numbers or a negative w or h is InputError naming the file and line.
std::vector<cv::Rect2d> ReadOtbGroundTruth(const std::string& path);

// The scores of one target over the N frames that have a ground-truth box, following the OTB
// toolkit (perfPlot.m, calcSeqErrRobust.m):
//   IoU(f)      = |P ∩ G| / |P ∪ G| of the predicted and true boxes as continuous rectangles;
//   success(t)  = #{f : IoU(f) > t} / N, strictly greater, for t = k / 20, k = 0..20;
//   success_auc = (1/21) sum_k success(k / 20), so a perfect track scores 20/21 = 0.952
//                 (no IoU exceeds 1) and a track never overlapping the truth 0;
//   error(f)    = distance between the boxes' centres (x + w/2, y + h/2);
//   precision_20 = #{f : error(f) <= 20} / N;
//   mean_iou    = (1/N) sum_f IoU(f).
// All are 0 when N = 0.
struct TrackingScores {
  int frames = 0;               // N: frames with a ground-truth box
  double success_auc = 0.0;     // mean over thresholds 0, 0.05, ..., 1 of success rate
  double precision_20 = 0.0;    // share of frames with centre error <= 20 px
  std::vector<double> success;  // success rate per threshold (21 values)
  double mean_iou = 0.0;
};

// Scores a sequence of predicted boxes against ground truth, frame by frame (both indexed by
// frame). A frame without a prediction (beyond the end of `predicted`, or an empty box: not
// found) has IoU 0 and an infinite centre error; frames whose ground truth is empty (object not
// visible) are skipped, as the LaSOT toolkit does; the OTB toolkit keeps them in the
// denominator (its OTB-2013 sequences have a box in every frame). The first frame is scored as
// predicted (the OTB toolkit replaces it with the ground truth). Predictions beyond the end of
// `truth` are ignored.
TrackingScores ScoreTracking(const std::vector<cv::Rect2d>& predicted,
                             const std::vector<cv::Rect2d>& truth);

}  // namespace attend
