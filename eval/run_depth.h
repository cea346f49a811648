// The depth of a run's targets (issue 44, SPEC 3.3's disparity_px and position_m) as `attend
// compare` and `attend report` show it (docs/COMPARE.md): per run, how many target-frames have
// a disparity or a position and their mean uncertainty; for the targets two runs share (the
// matches of eval/run_comparison.h), how far apart the runs put them; and each target's track
// seen from above (X, Z) for the report's top view.
//
// A target-frame is a target seen in a frame: state new, tracked or resumed (Visible). Only
// those carry a depth.
#pragma once

#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "io/frame_record.h"

namespace attend {

// One run's depth.
struct RunDepth {
  int target_frames = 0;   // targets seen, summed over the frames
  int with_disparity = 0;  // of those, with a disparity
  int with_position = 0;   // with a position
  // Means over the target-frames that have them (NaN when none): the disparity's standard
  // deviation (input pixels), the depth Z (metres) and its standard deviation.
  double mean_disparity_sd_px = std::numeric_limits<double>::quiet_NaN();
  double mean_depth_m = std::numeric_limits<double>::quiet_NaN();
  double mean_depth_sd_m = std::numeric_limits<double>::quiet_NaN();
  // Whether the run has any depth to show (a stereo run with depth.method set).
  bool any() const { return with_disparity > 0 || with_position > 0; }
};

RunDepth SummariseDepth(const std::vector<FrameRecord>& frames);

// A matched pair of targets (run A's id_a, run B's id_b) over the frames both runs see it in.
struct TargetDepthDifference {
  int id_a = -1;
  int id_b = -1;
  int disparity_frames = 0;  // frames where both have a disparity
  // Mean of B's disparity minus A's, input pixels (NaN without such frames).
  double mean_disparity_difference_px = std::numeric_limits<double>::quiet_NaN();
  int position_frames = 0;  // frames where both have a position
  // Mean Euclidean distance |p_B - p_A| and mean Z_B - Z_A, metres (NaN without such frames).
  double mean_distance_m = std::numeric_limits<double>::quiet_NaN();
  double mean_depth_difference_m = std::numeric_limits<double>::quiet_NaN();
};

struct DepthComparison {
  RunDepth a, b;
  std::vector<TargetDepthDifference> targets;  // the matched pairs, in their order
  // Over every frame of every pair: the mean |disparity_B - disparity_A| (pixels) and mean
  // distance (metres); NaN when no frame has both.
  double mean_abs_disparity_difference_px = std::numeric_limits<double>::quiet_NaN();
  double mean_distance_m = std::numeric_limits<double>::quiet_NaN();
};

// None when neither run has a depth; else each run's summary and, for each matched pair of
// `pairs` (A's id, B's id), the differences in the frames both runs have.
std::optional<DepthComparison> CompareDepth(const std::vector<FrameRecord>& a,
                                            const std::vector<FrameRecord>& b,
                                            const std::vector<std::pair<int, int>>& pairs);

// {"target_frames", "with_disparity", "with_position", "mean_disparity_sd_px",
// "mean_depth_m", "mean_depth_sd_m"}; NaN as null.
nlohmann::ordered_json RunDepthToJson(const RunDepth& depth);
// {"a": RunDepth, "b": RunDepth, "mean_abs_disparity_difference_px", "mean_distance_m",
// "targets": [{"a", "b", "disparity_frames", "mean_disparity_difference_px",
// "position_frames", "mean_distance_m", "mean_depth_difference_m"}]}; null for none.
nlohmann::ordered_json DepthComparisonToJson(const std::optional<DepthComparison>& comparison);

// One target's positions seen from above: X (right) and Z (forward), metres, in frame order.
struct TopViewTrack {
  int id = 0;
  std::vector<int> frames;
  std::vector<double> x_m, z_m;
};

// The tracks of the targets seen with a (finite) position, by id.
std::vector<TopViewTrack> TopViewTracks(const std::vector<FrameRecord>& frames);

}  // namespace attend
