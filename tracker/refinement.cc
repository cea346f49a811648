#include "tracker/refinement.h"

#include <algorithm>
#include <utility>

namespace attend {
namespace tracker_internal {

namespace {

float SquaredDistance(const float* a, const float* b) {
  const float d0 = a[0] - b[0], d1 = a[1] - b[1], d2 = a[2] - b[2];
  return d0 * d0 + d1 * d1 + d2 * d2;
}

}  // namespace

void MarkMatched(const TemplateLevel& t, const Hierarchy& h, int l, cv::Point displacement,
                 float t_colour, std::vector<uint8_t>* in_target) {
  const float t2 = t_colour * t_colour;
  const BipLevel& level = h.bip->level(l);
  for (int y = t.cells.y; y < t.cells.y + t.cells.height; ++y) {
    for (int x = t.cells.x; x < t.cells.x + t.cells.width; ++x) {
      const size_t i = t.Index(x, y);
      if (t.weight[i] <= 0.f) continue;
      const int cell = h.Cell(l, x + displacement.x, y + displacement.y);
      if (cell < 0 || !level.hom[cell] ||
          SquaredDistance(&t.colour[3 * i], level.Feature(cell)) >= t2) {
        continue;
      }
      const int r = h.region[l][cell];
      if (r >= 0) (*in_target)[r] = 1;
    }
  }
}

void Refine(const Hierarchy& h, const cv::Rect& roi, float t_refine,
            std::vector<uint8_t>* in_target) {
  const std::vector<uint8_t> first = *in_target;
  const float t2 = t_refine * t_refine;
  for (int l = 0; l < h.bip->num_levels(); ++l) {
    const BipLevel& level = h.bip->level(l);
    const std::vector<int32_t>& region = h.region[l];
    const cv::Rect cells = CellsInside(roi, l);
    auto consider = [&](int q, int n) {
      const int rn = region[n];
      if (rn < 0 || first[rn] || (*in_target)[rn]) return;
      if (SquaredDistance(level.Feature(q), level.Feature(n)) < t2) (*in_target)[rn] = 1;
    };
    const int ox = h.origin.x >> l, oy = h.origin.y >> l;
    for (int y = std::max(cells.y - oy, 0); y < std::min(cells.y + cells.height - oy, level.rows);
         ++y) {
      for (int x = std::max(cells.x - ox, 0); x < std::min(cells.x + cells.width - ox, level.cols);
           ++x) {
        const int q = y * level.cols + x;
        if (!level.hom[q] || region[q] < 0 || !first[region[q]]) continue;
        for (int dy = -1; dy <= 1; ++dy) {
          for (int dx = -1; dx <= 1; ++dx) {
            const int nx = x + dx, ny = y + dy;
            if ((dx == 0 && dy == 0) || nx < 0 || ny < 0 || nx >= level.cols || ny >= level.rows ||
                !cells.contains({nx + ox, ny + oy})) {
              continue;
            }
            const int n = ny * level.cols + nx;
            if (level.hom[n]) consider(q, n);
          }
        }
      }
    }
    // Virtual neighbours through the explicit edges.
    for (const uint64_t edge : level.edges) {
      const int a = static_cast<int>(edge >> 32), b = static_cast<int>(edge & 0xffffffffu);
      for (const auto& [q, n] : {std::pair<int, int>{a, b}, std::pair<int, int>{b, a}}) {
        if (level.IsVirtual(q) || region[q] < 0 || !first[region[q]]) continue;
        const int qx = q % level.cols + ox, qy = q / level.cols + oy;
        if (cells.contains({qx, qy})) consider(q, n);
      }
    }
  }
}

void PaintTarget(const Hierarchy& h, const std::vector<uint8_t>& in_target, const cv::Rect& roi,
                 cv::Size frame_size, cv::Mat* mask) {
  mask->create(frame_size, CV_8UC1);
  mask->setTo(0);
  const BipLevel& base = h.bip->level(0);
  const cv::Rect inside = roi & cv::Rect(h.origin, h.size);
  for (int y = inside.y; y < inside.y + inside.height; ++y) {
    uchar* out = mask->ptr<uchar>(y);
    const int row = (y - h.origin.y) * base.cols - h.origin.x;
    for (int x = inside.x; x < inside.x + inside.width; ++x) {
      const int cell = row + x;
      if (!base.hom[cell]) continue;
      const int r = h.region[0][cell];
      if (r >= 0 && in_target[r]) out[x] = 255;
    }
  }
}

}  // namespace tracker_internal
}  // namespace attend
