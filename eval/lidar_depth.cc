#include "eval/lidar_depth.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "util/median.h"

namespace attend {

double LidarDepthInBox(const FrameTruth& frame, const cv::Rect2d& box) {
  const cv::Rect2d inner(box.x + 0.25 * box.width, box.y + 0.25 * box.height, 0.5 * box.width,
                         0.5 * box.height);
  std::vector<double> depths;
  for (const TruthPoint& p : frame.points) {
    if (p.u >= inner.x && p.u < inner.x + inner.width && p.v >= inner.y &&
        p.v < inner.y + inner.height) {
      depths.push_back(p.depth_m);
    }
  }
  if (static_cast<int>(depths.size()) < kMinLidarPoints) {
    return std::numeric_limits<double>::quiet_NaN();
  }
  return MedianOf(depths);
}

LidarDepthScores EvaluateLidarDepth(const std::vector<FrameRecord>& frames,
                                    const SceneTruth& truth) {
  std::vector<double> relative, absolute;
  for (const FrameRecord& record : frames) {
    const auto it = truth.find(record.frame);
    if (it == truth.end()) continue;
    for (const TargetRecord& target : record.targets) {
      if (!Visible(target.state) || !target.has_position) continue;
      const double lidar = LidarDepthInBox(it->second, cv::Rect2d(target.bbox));
      if (!std::isfinite(lidar)) continue;
      const double error = std::abs(target.position_m[2] - lidar);
      absolute.push_back(error);
      relative.push_back(error / lidar);
    }
  }
  LidarDepthScores scores;
  scores.count = static_cast<int>(relative.size());
  if (scores.count == 0) return scores;
  scores.share_within_10_percent =
      static_cast<double>(
          std::count_if(relative.begin(), relative.end(), [](double r) { return r <= 0.1; })) /
      scores.count;
  scores.median_relative_error = MedianOf(relative);
  scores.median_abs_error_m = MedianOf(absolute);
  return scores;
}

}  // namespace attend
