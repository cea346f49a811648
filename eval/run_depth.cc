#include "eval/run_depth.h"

#include <cmath>
#include <limits>
#include <map>
#include <opencv2/core.hpp>

#include "util/json_text.h"

namespace attend {

namespace {

// A running mean of finite values.
struct Mean {
  double sum = 0.0;
  int count = 0;
  void Add(double value) {
    if (std::isfinite(value)) sum += value, ++count;
  }
  double value() const {
    return count > 0 ? sum / count : std::numeric_limits<double>::quiet_NaN();
  }
};

// The target `id` of `record` when it is seen there; null otherwise.
const TargetRecord* SeenTarget(const FrameRecord& record, int id) {
  for (const TargetRecord& target : record.targets) {
    if (target.id == id && Visible(target.state)) return &target;
  }
  return nullptr;
}

}  // namespace

RunDepth SummariseDepth(const std::vector<FrameRecord>& frames) {
  RunDepth depth;
  Mean disparity_sd, z, z_sd;
  for (const FrameRecord& record : frames) {
    for (const TargetRecord& target : record.targets) {
      if (!Visible(target.state)) continue;
      ++depth.target_frames;
      if (std::isfinite(target.disparity_px)) {
        ++depth.with_disparity;
        disparity_sd.Add(target.disparity_sd_px);
      }
      if (target.has_position) {
        ++depth.with_position;
        z.Add(target.position_m[2]);
        z_sd.Add(target.position_sd_m[2]);
      }
    }
  }
  depth.mean_disparity_sd_px = disparity_sd.value();
  depth.mean_depth_m = z.value();
  depth.mean_depth_sd_m = z_sd.value();
  return depth;
}

std::optional<DepthComparison> CompareDepth(const std::vector<FrameRecord>& a,
                                            const std::vector<FrameRecord>& b,
                                            const std::vector<std::pair<int, int>>& pairs) {
  DepthComparison comparison;
  comparison.a = SummariseDepth(a);
  comparison.b = SummariseDepth(b);
  if (!comparison.a.any() && !comparison.b.any()) return std::nullopt;
  std::map<int, const FrameRecord*> frames_b;
  for (const FrameRecord& record : b) frames_b[record.frame] = &record;
  Mean all_disparity, all_distance;
  for (const auto& [id_a, id_b] : pairs) {
    TargetDepthDifference difference;
    difference.id_a = id_a;
    difference.id_b = id_b;
    Mean disparity, distance, dz;
    for (const FrameRecord& record_a : a) {
      const auto found = frames_b.find(record_a.frame);
      if (found == frames_b.end()) continue;
      const TargetRecord* ta = SeenTarget(record_a, difference.id_a);
      const TargetRecord* tb = SeenTarget(*found->second, difference.id_b);
      if (ta == nullptr || tb == nullptr) continue;
      if (std::isfinite(ta->disparity_px) && std::isfinite(tb->disparity_px)) {
        const double d = tb->disparity_px - ta->disparity_px;
        disparity.Add(d);
        all_disparity.Add(std::abs(d));
      }
      if (ta->has_position && tb->has_position) {
        const double norm = cv::norm(tb->position_m - ta->position_m);
        distance.Add(norm);
        all_distance.Add(norm);
        dz.Add(tb->position_m[2] - ta->position_m[2]);
      }
    }
    difference.disparity_frames = disparity.count;
    difference.mean_disparity_difference_px = disparity.value();
    difference.position_frames = distance.count;
    difference.mean_distance_m = distance.value();
    difference.mean_depth_difference_m = dz.value();
    comparison.targets.push_back(difference);
  }
  comparison.mean_abs_disparity_difference_px = all_disparity.value();
  comparison.mean_distance_m = all_distance.value();
  return comparison;
}

nlohmann::ordered_json RunDepthToJson(const RunDepth& depth) {
  return {{"target_frames", depth.target_frames},
          {"with_disparity", depth.with_disparity},
          {"with_position", depth.with_position},
          {"mean_disparity_sd_px", FiniteOrNull(depth.mean_disparity_sd_px)},
          {"mean_depth_m", FiniteOrNull(depth.mean_depth_m)},
          {"mean_depth_sd_m", FiniteOrNull(depth.mean_depth_sd_m)}};
}

nlohmann::ordered_json DepthComparisonToJson(const std::optional<DepthComparison>& comparison) {
  if (!comparison) return nullptr;
  nlohmann::ordered_json targets = nlohmann::ordered_json::array();
  for (const TargetDepthDifference& t : comparison->targets) {
    targets.push_back({{"a", t.id_a},
                       {"b", t.id_b},
                       {"disparity_frames", t.disparity_frames},
                       {"mean_disparity_difference_px", FiniteOrNull(t.mean_disparity_difference_px)},
                       {"position_frames", t.position_frames},
                       {"mean_distance_m", FiniteOrNull(t.mean_distance_m)},
                       {"mean_depth_difference_m", FiniteOrNull(t.mean_depth_difference_m)}});
  }
  return {{"a", RunDepthToJson(comparison->a)},
          {"b", RunDepthToJson(comparison->b)},
          {"mean_abs_disparity_difference_px", FiniteOrNull(comparison->mean_abs_disparity_difference_px)},
          {"mean_distance_m", FiniteOrNull(comparison->mean_distance_m)},
          {"targets", targets}};
}

std::vector<TopViewTrack> TopViewTracks(const std::vector<FrameRecord>& frames) {
  std::map<int, TopViewTrack> by_id;
  for (const FrameRecord& record : frames) {
    for (const TargetRecord& target : record.targets) {
      if (!Visible(target.state) || !target.has_position) continue;
      // The reader refuses non-finite positions; records made in memory are held to it too.
      if (!std::isfinite(target.position_m[0]) || !std::isfinite(target.position_m[2])) continue;
      TopViewTrack& track = by_id[target.id];
      track.id = target.id;
      track.frames.push_back(record.frame);
      track.x_m.push_back(target.position_m[0]);
      track.z_m.push_back(target.position_m[2]);
    }
  }
  std::vector<TopViewTrack> tracks;
  for (auto& entry : by_id) tracks.push_back(std::move(entry.second));
  return tracks;
}

}  // namespace attend
