#include "tracker/roi_pyramid.h"

#include <algorithm>

#include "pyramid/similarity.h"
#include "util/error.h"
#include "util/timer.h"

namespace attend {
namespace tracker_internal {

void Hierarchy::LabelRegions() {
  const int levels = bip->num_levels();
  region.resize(levels);
  regions = 0;
  for (int l = levels - 1; l >= 0; --l) {
    const BipLevel& level = bip->level(l);
    std::vector<int32_t>& labels = region[l];
    labels.assign(level.num_ids(), -1);
    for (int id = 0; id < level.num_ids(); ++id) {
      if (!level.Exists(id)) continue;
      const int parent = level.parent[id];
      labels[id] = parent < 0 ? regions++ : region[l + 1][parent];
    }
  }
}

cv::Rect CellsInside(const cv::Rect& box, int l) {
  const int size = 1 << l;
  const int x0 = (box.x + size - 1) >> l, y0 = (box.y + size - 1) >> l;
  const int x1 = (box.x + box.width) >> l, y1 = (box.y + box.height) >> l;
  return {x0, y0, std::max(0, x1 - x0), std::max(0, y1 - y0)};
}

cv::Rect Aligned(const cv::Rect& bounds) {
  const int x0 = bounds.x / kAlignment * kAlignment, y0 = bounds.y / kAlignment * kAlignment;
  return {x0, y0, bounds.x + bounds.width - x0, bounds.y + bounds.height - y0};
}

void BuildHierarchy(const cv::Mat& frame, const cv::Mat& skin, TrackSimilarity similarity,
                    const cv::Mat& mask, cv::Rect bounds, int schedule_side, float t_max,
                    Hierarchy* hierarchy, const cv::Mat& cylinder) {
  bounds = Aligned(bounds);
  hierarchy->origin = bounds.tl();
  hierarchy->size = bounds.size();
  cv::Mat features;
  if (similarity == TrackSimilarity::kSkin) {
    ClassSimilarity::Features(skin(bounds), &features);
    hierarchy->bip =
        &hierarchy->builder.Build(features, ClassSimilarity(), mask(bounds), schedule_side);
  } else {
    if (cylinder.empty()) {
      HsvSimilarity::Features(frame(bounds), &features);
    } else {
      features = cylinder(bounds);
    }
    hierarchy->bip =
        &hierarchy->builder.Build(features, HsvSimilarity(t_max), mask(bounds), schedule_side);
  }
  hierarchy->LabelRegions();
}

void RoiPyramids::Merge(size_t a, size_t b, std::vector<cv::Rect>* groups,
                        std::vector<cv::Rect>* spans) {
  (*groups)[a] = Aligned((*groups)[a] | (*groups)[b]);
  (*spans)[a] |= (*spans)[b];
  groups->erase(groups->begin() + static_cast<std::ptrdiff_t>(b));
  spans->erase(spans->begin() + static_cast<std::ptrdiff_t>(b));
  for (int& g : group_of_) {
    if (g == static_cast<int>(b)) {
      g = static_cast<int>(a);
    } else if (g > static_cast<int>(b)) {
      --g;
    }
  }
}

void RoiPyramids::Release() {
  for (auto& pool : pools_) {
    for (auto& h : pool) h->Release();
  }
}

Hierarchy& RoiPyramids::Pyramid(TrackSimilarity similarity, size_t index) {
  auto& pool = pools_[similarity == TrackSimilarity::kSkin ? 1 : 0];
  while (pool.size() <= index) pool.push_back(std::make_unique<Hierarchy>(pool_));
  return *pool[index];
}

const Hierarchy* RoiPyramids::PartOf(TrackSimilarity similarity, size_t target) const {
  if (target >= group_of_.size() || group_of_[target] < 0) return nullptr;
  return pools_[similarity == TrackSimilarity::kSkin ? 1 : 0][group_of_[target]].get();
}

int RoiPyramids::Build(const cv::Mat& frame, const cv::Mat& skin, const cv::Mat& cylinder,
                       TrackSimilarity similarity, const std::vector<cv::Rect>& rois, float t_max,
                       bool in_parts, double* segmentation_ms) {
  // One pyramid over the union of the ROIs (4.3).
  union_mask_.create(frame.size(), CV_8UC1);
  union_mask_.setTo(0);
  bool any = false;
  cv::Rect bounds;
  for (const cv::Rect& roi : rois) {
    if (roi.empty()) continue;
    union_mask_(roi).setTo(255);
    bounds = any ? bounds | roi : roi;
    any = true;
  }
  if (!any) return 0;
  if (similarity == TrackSimilarity::kSkin) {
    ATTEND_CHECK(skin.type() == CV_8UC1 && skin.size() == frame.size())
        << "skin targets need the frame's binary skin map";
  }
  // The pyramid over the union of the ROIs is built in parts: ROIs whose aligned crops
  // overlap or touch share a part, and parts are apart by at least a pixel outside every
  // ROI. No vertex of one part is linked to, or adjacent to, a vertex of another, at any
  // level, and every part links with the thresholds of the whole union's crop. A part's
  // crop starts on a multiple of kAlignment, as the union's does, so their cells agree up
  // to level kMaxTemplateLevel; above it they may not, and a regular cell there needs
  // 2^(kMaxTemplateLevel + 1) pixels square inside the ROIs: when a part's ROIs could hold
  // one, the pyramid is built whole. Each part is then exactly the union pyramid's
  // restriction to it (the template follows the whole pyramid's height, see MakeTemplate),
  // and the parts cost what their crops cost, not what the bounding box of every ROI
  // would.
  std::vector<cv::Rect> groups;  // aligned crops
  std::vector<cv::Rect> spans;   // the bounding box of each group's ROIs
  group_of_.assign(rois.size(), -1);
  for (size_t i = 0; i < rois.size(); ++i) {
    if (rois[i].empty()) continue;
    group_of_[i] = static_cast<int>(groups.size());
    groups.push_back(Aligned(rois[i]));
    spans.push_back(rois[i]);
  }
  for (bool merged = true; merged;) {
    merged = false;
    for (size_t a = 0; a < groups.size() && !merged; ++a) {
      for (size_t b = a + 1; b < groups.size() && !merged; ++b) {
        const cv::Rect grown(groups[a].x - 1, groups[a].y - 1, groups[a].width + 2,
                             groups[a].height + 2);
        if ((grown & groups[b]).empty()) continue;
        Merge(a, b, &groups, &spans);
        merged = true;
      }
    }
  }
  constexpr int kUnaligned = 2 * kAlignment;
  const bool whole_pyramid =
      !in_parts || std::any_of(spans.begin(), spans.end(), [](const cv::Rect& span) {
        return span.width >= kUnaligned && span.height >= kUnaligned;
      });
  while (whole_pyramid && groups.size() > 1) Merge(0, 1, &groups, &spans);
  const cv::Rect whole = Aligned(bounds);
  const int schedule_side = std::min(whole.width, whole.height);
  const Stopwatch segmentation;
  int levels = 0;
  for (size_t g = 0; g < groups.size(); ++g) {
    Hierarchy& part = Pyramid(similarity, g);
    BuildHierarchy(frame, skin, similarity, union_mask_, groups[g], schedule_side, t_max, &part,
                   cylinder);
    levels = std::max(levels, part.bip->num_levels());
  }
  *segmentation_ms += segmentation.ElapsedMs();
  return levels;
}

}  // namespace tracker_internal
}  // namespace attend
