// The OTB one-pass evaluation of a track (SPEC 4): success AUC over IoU thresholds 0:0.05:1
// and precision at 20 px, of Wu, Lim and Yang, "Online Object Tracking: A Benchmark", CVPR
// 2013. docs/TRACKING.md has the definitions with worked examples; io/tracking_files.h reads
// and writes the boxes.
#pragma once

#include <opencv2/core.hpp>
#include <vector>

namespace attend {

// The scores of one target over the N frames that have a ground-truth box, following the OTB
// toolkit (perfPlot.m, calcSeqErrRobust.m):
//   IoU(f)      = |P ∩ G| / |P ∪ G| of the predicted and true boxes as continuous rectangles;
//   success(t)  = #{f : IoU(f) > t} / N, strictly greater, for t = k / 20, k = 0..20;
//   success_auc = (1/21) sum_k success(k / 20), so a perfect track scores 20/21 = 0.952
//                 (no IoU exceeds 1) and a track never overlapping the truth 0;
//   error(f)    = distance between the boxes' centres (x + w/2, y + h/2);
//   precision(t) = #{f : error(f) <= t} / N for t = 0, 1, ..., 50 px (the toolkit's precision
//                 plot), and precision_20 = precision(20);
//   mean_iou    = (1/N) sum_f IoU(f).
// All are 0 when N = 0.
struct TrackingScores {
  int frames = 0;               // N: frames with a ground-truth box
  double success_auc = 0.0;     // mean over thresholds 0, 0.05, ..., 1 of success rate
  double precision_20 = 0.0;    // share of frames with centre error <= 20 px
  std::vector<double> success;  // success rate per threshold (21 values)
  std::vector<double> precision;  // share of frames with centre error <= t px, t = 0..50
  double mean_iou = 0.0;
};

// The thresholds of the success curve (0, 0.05, ..., 1: 21 values) and of the precision curve
// (0, 1, ..., 50 px: 51 values), in the order of TrackingScores::success and ::precision.
const std::vector<double>& SuccessThresholds();
const std::vector<double>& PrecisionThresholds();

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
