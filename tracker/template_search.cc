#include "tracker/template_search.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "util/vector_clones.h"

namespace attend {
namespace tracker_internal {

namespace {

// Template weights in the search are fixed point, 1 = kWeightOne, so that sums are exact and
// do not depend on their order.
constexpr double kWeightOne = 65536.0;

// The colour overlap an appearance match needs besides its score: the correlation alone
// may follow an occluder or the background that took the target's place.
constexpr double kMinAppearanceOverlap = 0.1;

// PlacedOverlap() is compiled for AVX2 and for SSE2, with the same results
// (util/vector_clones.h).

// The weighted overlap of a template (planar colour t0..t2 and weight w, `width` x `height`
// cells) placed on ROI cells (planar r0..r2, rows `stride` apart, NaN where no regular vertex):
// `total` minus the weight of the template cells whose squared colour distance to the cell under
// them is not below `limit` (eq. 4.6). Rows are scored in order and scoring stops as soon as
// the result is <= `bar`; the result is then some value <= `bar`.
ATTEND_VECTOR_CLONES int64_t PlacedOverlap(const float* t0, const float* t1, const float* t2,
                                           const int32_t* w, int width, int height, const float* r0,
                                           const float* r1, const float* r2, size_t stride,
                                           float limit, int64_t total, int64_t bar) {
  int64_t score = total;
  for (int row = 0; row < height && score > bar; ++row) {
    int32_t missed = 0;
    for (int i = 0; i < width; ++i) {
      const float a = t0[i] - r0[i], b = t1[i] - r1[i], c = t2[i] - r2[i];
      const float d = a * a + b * b + c * c;
      missed += d < limit ? 0 : w[i];
    }
    score -= missed;
    t0 += width, t1 += width, t2 += width, w += width;
    r0 += stride, r1 += stride, r2 += stride;
  }
  return score;
}

// One level's displacements, ready to score.
struct Scan {
  const SearchPlanes& planes;
  const cv::Rect& roi;  // the ROI's cells
  float limit;          // T_c squared
  int64_t total;        // the template's weight
  int64_t accepted;     // the smallest weight sum that is accepted
  cv::Point prior;      // the previous motion, cells
  double sigma;         // of the motion prior, cells
  const std::vector<cv::Point>& displacements;

  // The overlap of displacement d (PlacedOverlap: exact when above `bar`).
  int64_t Overlap(const cv::Point& d, int64_t bar) const {
    const cv::Rect& occupied = planes.occupied;
    const size_t from =
        static_cast<size_t>(occupied.y + d.y - roi.y) * roi.width + (occupied.x + d.x - roi.x);
    return PlacedOverlap(planes.colour[0].data(), planes.colour[1].data(), planes.colour[2].data(),
                         planes.weight.data(), occupied.width, occupied.height,
                         &planes.roi[0][from], &planes.roi[1][from], &planes.roi[2][from],
                         roi.width, limit, total, bar);
  }
  // The motion prior of displacement d.
  double Prior(const cv::Point& d) const {
    const double ex = d.x - prior.x, ey = d.y - prior.y;
    return std::exp(-(ex * ex + ey * ey) / (2 * sigma * sigma));
  }
};

// The best of a scan: its displacement and weighted overlap (in weight units).
struct Best {
  bool found = false;
  cv::Point d;
  int64_t overlap = 0;
  double correlation = 0.0;
  bool scored = false;
};

// The thesis's search: the largest overlap above the bar. Every displacement is scored, row by
// row of the template; one stops being scored as soon as the weight it has missed shows that
// it can neither be accepted nor beat the best so far. The accepted result is that of the
// exhaustive search, ties included.
Best BestOverlap(const Scan& scan) {
  Best best;
  best.overlap = scan.accepted - 1;
  for (const cv::Point& d : scan.displacements) {
    const int64_t score = scan.Overlap(d, best.overlap);
    if (score > best.overlap) best = {true, d, score};
  }
  return best;
}

// Each accepted overlap weighed by the motion prior: among displacements that match, the
// target most likely moved little. Displacements come nearest first, so the prior only
// falls, and the search stops once even a whole overlap could no longer win.
Best BestNearMotion(const Scan& scan) {
  Best best;
  best.overlap = scan.accepted - 1;
  double best_weighted = 0.0;
  for (const cv::Point& d : scan.displacements) {
    const double k = scan.Prior(d);
    if (best.found && k * scan.total <= best_weighted) break;
    const int64_t bar = std::max<int64_t>(
        scan.accepted - 1, best.found ? static_cast<int64_t>(std::floor(best_weighted / k)) : 0);
    const int64_t score = scan.Overlap(d, bar);
    if (score > bar && k * score > best_weighted) {
      best_weighted = k * score;
      best = {true, d, score};
    }
  }
  return best;
}

// The appearance joins the overlap. The score is not monotone in the search order, so every
// displacement is scored exactly; the prior-weighted score is the one accepted (a far
// displacement needs a strong match), and some colour overlap is needed too: the correlation
// alone may follow an occluder or the background that took the target's place.
Best BestWithAppearance(const Scan& scan, const SearchScoring& scoring, int l) {
  Best best;
  best.overlap = scan.accepted - 1;
  const double share = scoring.appearance_share;
  double best_score = 0.0;
  for (const cv::Point& d : scan.displacements) {
    const double k = scoring.motion_sigma > 0.f ? scan.Prior(d) : 1.0;
    if (k <= best_score) break;  // nearest first: k only falls
    const double c = std::max(0.0, scoring.appearance->At(d, l));
    const int64_t overlap = scan.Overlap(d, -1);
    const double score = k * ((1 - share) * static_cast<double>(overlap) / scan.total + share * c);
    if (score > best_score) {
      best_score = score;
      best.overlap = overlap;
      best.d = d;
      best.correlation = c;
      best.scored = true;
    }
  }
  best.found = best_score > scoring.min_score &&
               static_cast<double>(best.overlap) / scan.total >= kMinAppearanceOverlap;
  return best;
}

}  // namespace

void SearchPlanes::Load(const TemplateLevel& t, const BipLevel& level, const cv::Rect& roi_cells,
                        int ox, int oy, const std::vector<float>& distinct) {
  int x0 = std::numeric_limits<int>::max(), y0 = x0, x1 = -1, y1 = -1;
  for (int y = 0; y < t.cells.height; ++y) {
    const float* w = &t.weight[static_cast<size_t>(y) * t.cells.width];
    for (int x = 0; x < t.cells.width; ++x) {
      if (!(w[x] > 0.f)) continue;
      x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = y;
    }
  }
  total = 0;
  occupied = cv::Rect();
  if (x1 < 0) return;
  occupied = cv::Rect(t.cells.x + x0, t.cells.y + y0, x1 - x0 + 1, y1 - y0 + 1);
  const size_t cells = static_cast<size_t>(occupied.area());
  for (auto& plane : colour) plane.assign(cells, 0.f);
  weight.assign(cells, 0);
  for (int y = occupied.y; y < occupied.y + occupied.height; ++y) {
    for (int x = occupied.x; x < occupied.x + occupied.width; ++x) {
      const size_t i = t.Index(x, y);
      if (t.weight[i] <= 0.f) continue;
      const size_t j = static_cast<size_t>(y - occupied.y) * occupied.width + (x - occupied.x);
      for (int c = 0; c < 3; ++c) colour[c][j] = t.colour[3 * i + c];
      const float scale = distinct.empty() ? 1.f : distinct[ColourBin(&t.colour[3 * i])];
      weight[j] =
          std::max<int32_t>(1, static_cast<int32_t>(std::lround(t.weight[i] * scale * kWeightOne)));
      total += weight[j];
    }
  }
  const float none = std::numeric_limits<float>::quiet_NaN();
  for (auto& plane : roi) plane.resize(static_cast<size_t>(roi_cells.area()));
  size_t j = 0;
  for (int y = roi_cells.y; y < roi_cells.y + roi_cells.height; ++y) {
    const int row = (y - oy) * level.cols - ox;
    for (int x = roi_cells.x; x < roi_cells.x + roi_cells.width; ++x, ++j) {
      const int cell = row + x;
      const bool regular = level.hom[cell] != 0;
      const float* f = level.Feature(cell);
      for (int c = 0; c < 3; ++c) roi[c][j] = regular ? f[c] : none;
    }
  }
}

const std::vector<cv::Point>& SearchPlanes::Order(int dx0, int dx1, int dy0, int dy1,
                                                  cv::Point prior) {
  distance.clear();
  int largest = 0;
  for (int dy = dy0; dy <= dy1; ++dy) {
    for (int dx = dx0; dx <= dx1; ++dx) {
      const int ex = dx - prior.x, ey = dy - prior.y;
      distance.push_back(ex * ex + ey * ey);
      largest = std::max(largest, distance.back());
    }
  }
  bucket.assign(static_cast<size_t>(largest) + 2, 0);
  for (const int d : distance) ++bucket[static_cast<size_t>(d) + 1];
  for (size_t i = 1; i < bucket.size(); ++i) bucket[i] += bucket[i - 1];
  displacements.resize(distance.size());
  size_t i = 0;
  for (int dy = dy0; dy <= dy1; ++dy) {
    for (int dx = dx0; dx <= dx1; ++dx, ++i) {
      displacements[static_cast<size_t>(bucket[static_cast<size_t>(distance[i])]++)] = {dx, dy};
    }
  }
  return displacements;
}

Match TemplateSearch::SearchLevel(const Target& target, const Hierarchy& h, int l,
                                  const cv::Rect* window, const SearchScoring& scoring) {
  const cv::Rect roi = CellsInside(target.roi, l);
  planes_.Load(target.levels[l], h.bip->level(l), roi, h.origin.x >> l, h.origin.y >> l,
               target.appearance.distinct);
  if (planes_.total <= 0) return {};
  const cv::Rect& occupied = planes_.occupied;
  // Displacements that keep the occupied cells inside the ROI, nearest to the previous
  // motion first, so that among equal overlaps the nearest wins by coming first.
  int dx0 = roi.x - occupied.x, dx1 = roi.x + roi.width - (occupied.x + occupied.width);
  int dy0 = roi.y - occupied.y, dy1 = roi.y + roi.height - (occupied.y + occupied.height);
  if (window != nullptr) {
    dx0 = std::max(dx0, window->x), dx1 = std::min(dx1, window->x + window->width - 1);
    dy0 = std::max(dy0, window->y), dy1 = std::min(dy1, window->y + window->height - 1);
  }
  if (dx1 < dx0 || dy1 < dy0) return {};
  const cv::Point prior(
      static_cast<int>(std::lround(target.motion.x / static_cast<double>(1 << l))),
      static_cast<int>(std::lround(target.motion.y / static_cast<double>(1 << l))));
  // The smallest weight sum that is accepted (overlap > min_overlap).
  const int64_t total = planes_.total;
  const double min_overlap = scoring.min_overlap;
  int64_t accepted = static_cast<int64_t>(std::floor(min_overlap * total));
  while (accepted > 0 && static_cast<double>(accepted) / total > min_overlap) --accepted;
  while (static_cast<double>(accepted) / total <= min_overlap) ++accepted;
  const double sigma = std::max(
      1.0, scoring.motion_sigma * std::sqrt(static_cast<double>(target.box.area())) / (1 << l));
  const Scan scan{planes_, roi,   scoring.t_colour * scoring.t_colour,     total, accepted,
                  prior,   sigma, planes_.Order(dx0, dx1, dy0, dy1, prior)};
  const Best best = scoring.appearance != nullptr ? BestWithAppearance(scan, scoring, l)
                    : scoring.motion_sigma > 0.f  ? BestNearMotion(scan)
                                                  : BestOverlap(scan);
  Match match;
  match.correlation = best.correlation;
  match.scored = best.scored;
  if (!best.found) return match;
  match.found = true;
  match.level = l;
  match.displacement = best.d;
  match.overlap = static_cast<double>(best.overlap) / total;
  return match;
}

}  // namespace tracker_internal
}  // namespace attend
