#include "eval/tracking_scores.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "util/box.h"

namespace attend {

namespace {

constexpr int kThresholds = 21;  // 0, 0.05, ..., 1
constexpr int kPrecisionThresholds = 51;  // 0, 1, ..., 50 px
constexpr int kPrecisionPixels = 20;

bool IsEmpty(const cv::Rect2d& box) { return !(box.width > 0.0) || !(box.height > 0.0); }

// Intersection over union of two non-empty boxes, as areas of continuous rectangles (the OTB
// toolkit's calcRectInt gives the same value for its 1-based inclusive pixel boxes).

double CentreDistance(const cv::Rect2d& a, const cv::Rect2d& b) {
  return std::hypot((a.x + 0.5 * a.width) - (b.x + 0.5 * b.width),
                    (a.y + 0.5 * a.height) - (b.y + 0.5 * b.height));
}

}  // namespace

const std::vector<double>& SuccessThresholds() {
  static const std::vector<double> thresholds = [] {
    std::vector<double> values;
    for (int k = 0; k < kThresholds; ++k) values.push_back(k / 20.0);
    return values;
  }();
  return thresholds;
}

const std::vector<double>& PrecisionThresholds() {
  static const std::vector<double> thresholds = [] {
    std::vector<double> values;
    for (int t = 0; t < kPrecisionThresholds; ++t) values.push_back(t);
    return values;
  }();
  return thresholds;
}

TrackingScores ScoreTracking(const std::vector<cv::Rect2d>& predicted,
                             const std::vector<cv::Rect2d>& truth) {
  TrackingScores scores;
  scores.success.assign(kThresholds, 0.0);
  scores.precision.assign(kPrecisionThresholds, 0.0);
  double iou_sum = 0.0;
  for (size_t frame = 0; frame < truth.size(); ++frame) {
    if (IsEmpty(truth[frame])) continue;
    ++scores.frames;
    double iou = 0.0;
    double error = std::numeric_limits<double>::infinity();
    if (frame < predicted.size() && !IsEmpty(predicted[frame])) {
      iou = BoxIou(predicted[frame], truth[frame]);
      error = CentreDistance(predicted[frame], truth[frame]);
    }
    for (int k = 0; k < kThresholds; ++k) {
      // k / 20.0 is the double nearest to 0.05 k; 0.05 * k is not always.
      if (iou > k / 20.0) scores.success[k] += 1.0;
    }
    for (int t = 0; t < kPrecisionThresholds; ++t) {
      if (error <= t) scores.precision[t] += 1.0;
    }
    iou_sum += iou;
  }
  if (scores.frames == 0) return scores;
  double sum = 0.0;
  for (double& rate : scores.success) {
    rate /= scores.frames;
    sum += rate;
  }
  scores.success_auc = sum / kThresholds;
  for (double& rate : scores.precision) rate /= scores.frames;
  scores.precision_20 = scores.precision[kPrecisionPixels];
  scores.mean_iou = iou_sum / scores.frames;
  return scores;
}

}  // namespace attend
