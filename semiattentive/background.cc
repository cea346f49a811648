#include "semiattentive/background.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>

namespace attend {

namespace {

// What one pass over the labels counts of each region.
struct RegionCounts {
  int measured = 0;
  double disparity_sum = 0.0;
  int ground = 0;
  int border = 0;
  double height_sum = 0.0;  // metres above the ground, over the measured pixels (with a baseline)
};

std::vector<RegionCounts> CountRegions(const Segmentation& segmentation, const cv::Mat& disparity,
                                       const cv::Mat& measured, const GroundPlane& ground,
                                       double baseline_m) {
  // Heights above the ground need the plane and the baseline: B / slope is the camera's height.
  const bool heights = ground.valid && baseline_m > 0.0;
  const double camera_height = heights ? baseline_m / ground.slope : 0.0;
  const cv::Mat& labels = segmentation.labels;
  std::vector<RegionCounts> counts(segmentation.regions.size());
  const bool stereo = !disparity.empty();
  const int last_row = labels.rows - 1, last_column = labels.cols - 1;
  for (int y = 0; y < labels.rows; ++y) {
    const int* label = labels.ptr<int>(y);
    const float* d = stereo ? disparity.ptr<float>(y) : nullptr;
    const uint8_t* m = stereo ? measured.ptr<uint8_t>(y) : nullptr;
    const bool border_row = y == 0 || y == last_row;
    for (int x = 0; x < labels.cols; ++x) {
      if (label[x] < 0) continue;
      RegionCounts& c = counts[label[x]];
      if (border_row || x == 0 || x == last_column) ++c.border;
      if (!stereo || !m[x]) continue;
      ++c.measured;
      c.disparity_sum += d[x];
      if (ground.OnGround(y, d[x])) ++c.ground;
      // A pixel at the horizon or nearer infinity than the matcher resolves is far above.
      if (heights) {
        c.height_sum += d[x] > 0.5f ? camera_height - (y - ground.horizon_v) * baseline_m / d[x]
                                    : camera_height + 100.0;
      }
    }
  }
  return counts;
}

}  // namespace

const char* BackgroundKindName(BackgroundKind kind) {
  switch (kind) {
    case BackgroundKind::kGround: return "ground";
    case BackgroundKind::kNoDepth: return "no_depth";
    case BackgroundKind::kHigh: return "high";
    case BackgroundKind::kBorder: return "border";
    case BackgroundKind::kLarge: return "large";
    case BackgroundKind::kNone: break;
  }
  return "";
}

const cv::Mat& SceneAnalysis::WithoutBackground(const cv::Mat& saliency) {
  saliency.copyTo(without_);
  without_.setTo(0.f, regions_.mask);
  return without_;
}

double SceneAnalysis::WidthM(const Segmentation& segmentation, int region) const {
  if (baseline_m_ <= 0.0 || region < 0 || region >= static_cast<int>(regions_.disparity.size())) {
    return std::numeric_limits<double>::quiet_NaN();
  }
  const float d = regions_.disparity[region];
  if (!(d > 0.f)) return std::numeric_limits<double>::quiet_NaN();
  return segmentation.regions[region].bbox.width * baseline_m_ / d;
}

void SceneAnalysis::MarkTaken(std::vector<uint8_t>* taken) const {
  for (size_t r = 0; r < taken->size() && r < regions_.kind.size(); ++r) {
    if (regions_.kind[r] != BackgroundKind::kNone) (*taken)[r] = 1;
  }
}

bool SceneAnalysis::OnBackground(const cv::Mat& mask, const cv::Rect& box, int* frames) const {
  *frames = BackgroundShare(mask, box) > kMovedOnShare ? *frames + 1 : 0;
  return *frames >= kMovedOnFrames;
}

void SceneAnalysis::Analyse(const Segmentation& segmentation, const cv::Mat& disparity,
                            const cv::Mat& measured) {
  const bool stereo = !disparity.empty() && !measured.empty();
  Analyse(segmentation, disparity, measured,
          stereo ? FitGroundPlane(disparity, measured) : GroundPlane());
}

void SceneAnalysis::Analyse(const Segmentation& segmentation, const cv::Mat& disparity,
                            const cv::Mat& measured, const GroundPlane& ground) {
  const cv::Mat& labels = segmentation.labels;
  const bool stereo = !disparity.empty() && !measured.empty();
  regions_.ground = stereo ? ground : GroundPlane();
  const std::vector<RegionCounts> counts =
      CountRegions(segmentation, stereo ? disparity : cv::Mat(), stereo ? measured : cv::Mat(),
                   regions_.ground, baseline_m_);
  const bool heights = regions_.ground.valid && baseline_m_ > 0.0 && options_.max_height > 0.f;
  const size_t n = segmentation.regions.size();
  regions_.kind.assign(n, BackgroundKind::kNone);
  regions_.disparity.assign(n, std::numeric_limits<float>::quiet_NaN());
  const double border_pixels = std::max(1, 2 * (labels.cols + labels.rows) - 4);
  const double max_area = options_.max_area_fraction * static_cast<double>(labels.total());
  for (size_t r = 0; r < n; ++r) {
    const RegionCounts& c = counts[r];
    const double area = segmentation.regions[r].area;
    const bool has_depth = stereo && c.measured >= options_.min_measured * area && c.measured > 0;
    if (has_depth) regions_.disparity[r] = static_cast<float>(c.disparity_sum / c.measured);
    BackgroundKind kind = BackgroundKind::kNone;
    if (has_depth && c.ground >= options_.ground_share * c.measured) {
      kind = BackgroundKind::kGround;
    } else if (stereo && !has_depth && c.border > 0) {
      kind = BackgroundKind::kNoDepth;
    } else if (heights && c.height_sum > options_.max_height * c.measured) {
      kind = BackgroundKind::kHigh;
    } else if (options_.border_share < 1.f && c.border >= options_.border_share * border_pixels) {
      kind = BackgroundKind::kBorder;
    } else if (area > max_area) {
      kind = BackgroundKind::kLarge;
    }
    regions_.kind[r] = kind;
  }
  regions_.mask.create(labels.size(), CV_8UC1);
  for (int y = 0; y < labels.rows; ++y) {
    const int* label = labels.ptr<int>(y);
    uint8_t* out = regions_.mask.ptr<uint8_t>(y);
    for (int x = 0; x < labels.cols; ++x) {
      out[x] = label[x] >= 0 ? static_cast<uint8_t>(regions_.kind[label[x]]) : 0;
    }
  }
}

double SceneAnalysis::BackgroundShare(const cv::Mat& mask, const cv::Rect& box) const {
  const cv::Rect inside = box & cv::Rect(0, 0, mask.cols, mask.rows);
  if (inside.empty() || regions_.mask.size() != mask.size()) return 0.0;
  const int pixels = cv::countNonZero(mask(inside));
  if (pixels == 0) return 0.0;
  return static_cast<double>(cv::countNonZero(mask(inside) & regions_.mask(inside))) / pixels;
}

void SceneAnalysis::GroupByDepth(const Segmentation& segmentation,
                                 const std::vector<uint8_t>& taken, double max_area,
                                 std::vector<int>* members, double* area) const {
  if (options_.group_depth <= 0.f || members->empty() ||
      regions_.disparity.size() != segmentation.regions.size()) {
    return;
  }
  const float seed = regions_.disparity[members->front()];
  if (!(seed > 0.f)) return;
  // Half a pixel at least: the map's values step by whole pixels where it is not sub-pixel.
  const float tolerance = std::max(0.5f, options_.group_depth * seed);
  std::vector<uint8_t> in(segmentation.regions.size(), 0);
  for (const int region : *members) in[region] = 1;
  std::deque<int> frontier(members->begin(), members->end());
  const RegionAdjacency& graph = segmentation.adjacency;
  while (!frontier.empty()) {
    const int region = frontier.front();
    frontier.pop_front();
    for (const int* n = graph.NeighboursBegin(region); n != graph.NeighboursEnd(region); ++n) {
      if (in[*n] || taken[*n] || regions_.kind[*n] != BackgroundKind::kNone) continue;
      const float d = regions_.disparity[*n];
      const double n_area = segmentation.regions[*n].area;
      if (!(std::abs(d - seed) <= tolerance) || *area + n_area > max_area) continue;
      in[*n] = 1;
      members->push_back(*n);
      *area += n_area;
      frontier.push_back(*n);
    }
  }
}

}  // namespace attend
