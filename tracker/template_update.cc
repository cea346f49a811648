#include "tracker/template_update.h"

#include <cmath>

namespace attend {
namespace tracker_internal {

namespace {

// A shift in pixels as whole cells of level l.
int CellsOf(int pixels, int l) {
  return static_cast<int>(std::lround(pixels / static_cast<double>(1 << l)));
}

}  // namespace

std::vector<TemplateLevel> MakeTemplate(const Hierarchy& h, const std::vector<uint8_t>& in_target,
                                        const cv::Rect& keep, const std::vector<TemplateLevel>* old,
                                        cv::Point shift, int pyramid_levels, float alpha) {
  const int levels = std::min(pyramid_levels, kMaxTemplateLevel + 1);
  std::vector<TemplateLevel> result(levels);
  for (int l = 0; l < levels; ++l) {
    const bool built = l < h.bip->num_levels();
    const int dx = CellsOf(shift.x, l), dy = CellsOf(shift.y, l);
    // Window: the crop's cells, joined with the shifted old window. Above the part's levels
    // the whole pyramid's cells of the level hold every cell inside `keep` (which lies in
    // the crop), and so does the window.
    cv::Rect window = built ? cv::Rect((h.origin.x >> l), (h.origin.y >> l), h.bip->level(l).cols,
                                       h.bip->level(l).rows)
                            : CellsInside(keep, l);
    if (old != nullptr && l < static_cast<int>(old->size()) && !(*old)[l].cells.empty()) {
      window |= (*old)[l].cells + cv::Point(dx, dy);
    }
    const cv::Rect kept = CellsInside(keep, l) & window;
    TemplateLevel& t = result[l];
    t.cells = kept;
    t.colour.assign(3 * static_cast<size_t>(kept.area()), 0.f);
    t.area.assign(kept.area(), 0);
    t.weight.assign(kept.area(), 0.f);
    if (kept.empty()) continue;
    // Decayed old vertices first, then the new target's vertices over them.
    if (old != nullptr && l < static_cast<int>(old->size())) {
      const TemplateLevel& o = (*old)[l];
      for (int y = o.cells.y; y < o.cells.y + o.cells.height; ++y) {
        for (int x = o.cells.x; x < o.cells.x + o.cells.width; ++x) {
          const size_t i = o.Index(x, y);
          const float w = o.weight[i] - alpha;
          if (o.weight[i] <= 0.f || w <= 1e-6f || !kept.contains({x + dx, y + dy})) continue;
          const size_t j = t.Index(x + dx, y + dy);
          t.weight[j] = w;
          t.area[j] = o.area[i];
          std::copy(&o.colour[3 * i], &o.colour[3 * i] + 3, &t.colour[3 * j]);
        }
      }
    }
    if (!built) continue;
    const BipLevel& level = h.bip->level(l);
    for (int y = kept.y; y < kept.y + kept.height; ++y) {
      for (int x = kept.x; x < kept.x + kept.width; ++x) {
        const int cell = h.Cell(l, x, y);
        if (cell < 0 || !level.hom[cell]) continue;
        const int r = h.region[l][cell];
        if (r < 0 || !in_target[r]) continue;
        const size_t j = t.Index(x, y);
        t.weight[j] = 1.f;
        t.area[j] = level.area[cell];
        std::copy(level.Feature(cell), level.Feature(cell) + 3, &t.colour[3 * j]);
      }
    }
  }
  while (!result.empty() && result.back().Empty()) result.pop_back();
  return result;
}

int WorkingLevel(const std::vector<TemplateLevel>& levels, float working_area) {
  if (levels.empty()) return -1;
  const double base = levels[0].TotalArea();
  int working = 0;
  for (int l = 1; l < static_cast<int>(levels.size()); ++l) {
    if (base > 0 && levels[l].TotalArea() > working_area * base) working = l;
  }
  return working;
}

void Decay(float alpha, std::vector<TemplateLevel>* levels) {
  // A weight left at a rounding error of 0 (1 - k alpha in float) is 0, as in MakeTemplate:
  // the target is lost after 1 / alpha frames, not one more.
  for (TemplateLevel& level : *levels) {
    for (float& w : level.weight) w = w - alpha > 1e-6f ? w - alpha : 0.f;
  }
  while (!levels->empty() && levels->back().Empty()) levels->pop_back();
}

void MoveTemplate(cv::Point shift, std::vector<TemplateLevel>* levels) {
  for (size_t l = 0; l < levels->size(); ++l) {
    (*levels)[l].cells.x += CellsOf(shift.x, static_cast<int>(l));
    (*levels)[l].cells.y += CellsOf(shift.y, static_cast<int>(l));
  }
}

}  // namespace tracker_internal
}  // namespace attend
