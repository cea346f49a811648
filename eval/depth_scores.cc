#include "eval/depth_scores.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "util/box.h"
#include "util/median.h"

namespace attend {

namespace {

// -1 for none, as the JSON of these scores reads an unknown.
double MedianOrMinusOne(const std::vector<double>& values) {
  return values.empty() ? -1.0 : MedianOf(values);
}

double Share(int count, int total) { return total > 0 ? static_cast<double>(count) / total : -1.0; }

}  // namespace

DepthScores EvaluateTargetDepth(const std::vector<FrameRecord>& frames,
                                const std::vector<GtObject>& truth,
                                const DepthScoreOptions& options) {
  std::map<int, std::vector<const GtObject*>> by_frame;
  for (const GtObject& object : truth) {
    if (object.disparity.has_value() && object.visible_fraction >= options.min_visible &&
        object.box.area() > 0) {
      by_frame[object.frame].push_back(&object);
    }
  }
  std::vector<double> errors, depth_errors;
  int quarter = 0, one_sd = 0, two_sd = 0, with_sd = 0, near_within = 0;
  for (const FrameRecord& record : frames) {
    const auto objects = by_frame.find(record.frame);
    if (objects == by_frame.end()) continue;
    for (const TargetRecord& target : record.targets) {
      if (!Visible(target.state) || !std::isfinite(target.disparity_px)) continue;
      const GtObject* best = nullptr;
      double best_iou = options.match_iou;
      for (const GtObject* object : objects->second) {
        const double iou = BoxIou(cv::Rect2d(target.bbox), object->box);
        if (iou >= best_iou) {
          best_iou = iou;
          best = object;
        }
      }
      if (best == nullptr) continue;
      const double truth_px = *best->disparity;
      const double error = std::abs(target.disparity_px - truth_px);
      errors.push_back(error);
      quarter += error <= 0.25;
      if (std::isfinite(target.disparity_sd_px)) {
        ++with_sd;
        one_sd += error <= target.disparity_sd_px;
        two_sd += error <= 2.0 * target.disparity_sd_px;
      }
      if (truth_px >= options.near_disparity && target.disparity_px > 0.0) {
        const double relative = std::abs(truth_px / target.disparity_px - 1.0);
        depth_errors.push_back(relative);
        near_within += relative <= 0.02;
      }
    }
  }
  DepthScores scores;
  scores.matches = static_cast<int>(errors.size());
  if (errors.empty()) return scores;
  scores.median_abs_error_px = MedianOrMinusOne(errors);
  double sum = 0.0;
  for (const double e : errors) sum += e;
  scores.mean_abs_error_px = sum / errors.size();
  scores.share_within_quarter_px = Share(quarter, scores.matches);
  scores.near_matches = static_cast<int>(depth_errors.size());
  scores.median_depth_error = MedianOrMinusOne(depth_errors);
  scores.share_depth_within_2_percent = Share(near_within, scores.near_matches);
  scores.share_within_1_sd = Share(one_sd, with_sd);
  scores.share_within_2_sd = Share(two_sd, with_sd);
  return scores;
}

}  // namespace attend
