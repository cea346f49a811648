// The targets' depth against a LiDAR's (docs/STEREO3D.md, "Depth against the LiDAR"): each
// target seen in a frame (new, tracked or resumed) with a position in metres, whose box's inner
// half (half its width and height about its centre) holds at least kMinLidarPoints LiDAR
// points, against the median depth of those points. The inner half keeps the background that a
// box's corners hold out of the truth.
#pragma once

#include <vector>

#include "eval/scene_truth.h"
#include "io/frame_record.h"

namespace attend {

inline constexpr int kMinLidarPoints = 3;

struct LidarDepthScores {
  int count = 0;                          // target-frames scored
  double share_within_10_percent = -1.0;  // |Z - Z_lidar| / Z_lidar <= 0.1; -1 when count is 0
  double median_relative_error = -1.0;    // median |Z - Z_lidar| / Z_lidar
  double median_abs_error_m = -1.0;       // median |Z - Z_lidar|, metres
};

// The scores of `frames` (frames.jsonl, input pixels) against the points of `truth`.
LidarDepthScores EvaluateLidarDepth(const std::vector<FrameRecord>& frames,
                                    const SceneTruth& truth);

// The median depth of the points of `frame` inside the inner half of `box`; NaN when fewer than
// kMinLidarPoints lie there.
double LidarDepthInBox(const FrameTruth& frame, const cv::Rect2d& box);

}  // namespace attend
