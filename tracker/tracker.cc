#include "tracker/tracker.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <opencv2/imgproc.hpp>

#include "colour/colour.h"
#include "pyramid/bip.h"
#include "pyramid/segmentation.h"
#include "pyramid/similarity.h"
#include "tracker/tracker_impl.h"
#include "util/enum_table.h"
#include "util/error.h"
#include "util/timer.h"
#include "util/vector_clones.h"

namespace attend {

using namespace tracker_internal;

namespace {

float SquaredDistance(const float* a, const float* b) {
  const float d0 = a[0] - b[0], d1 = a[1] - b[1], d2 = a[2] - b[2];
  return d0 * d0 + d1 * d1 + d2 * d2;
}

// The cells of level l whose pixels lie inside `box` (level-0 pixels), in absolute cells.
cv::Rect CellsInside(const cv::Rect& box, int l) {
  const int size = 1 << l;
  const int x0 = (box.x + size - 1) >> l, y0 = (box.y + size - 1) >> l;
  const int x1 = (box.x + box.width) >> l, y1 = (box.y + box.height) >> l;
  return {x0, y0, std::max(0, x1 - x0), std::max(0, y1 - y0)};
}

// `bounds` grown to the top left to the nearest multiple of kAlignment, so that cells keep their
// absolute positions from frame to frame.
cv::Rect Aligned(const cv::Rect& bounds) {
  const int x0 = bounds.x / kAlignment * kAlignment, y0 = bounds.y / kAlignment * kAlignment;
  return {x0, y0, bounds.x + bounds.width - x0, bounds.y + bounds.height - y0};
}

// Builds `hierarchy` over the pixels of `mask` (frame size) in `bounds` (aligned), with the
// similarity's features and the threshold schedule of an image whose smaller side is
// `schedule_side` (0: the crop's).
void BuildHierarchy(const cv::Mat& frame, const cv::Mat& skin, TrackSimilarity similarity,
                    const cv::Mat& mask, cv::Rect bounds, int schedule_side, float t_max,
                    Hierarchy* hierarchy, const cv::Mat& cylinder = cv::Mat()) {
  bounds = Aligned(bounds);
  hierarchy->origin = bounds.tl();
  hierarchy->size = bounds.size();
  cv::Mat features;
  if (similarity == TrackSimilarity::kSkin) {
    ClassSimilarity::Features(skin(bounds), &features);
    hierarchy->bip =
        &hierarchy->builder.Build(features, ClassSimilarity(), mask(bounds), schedule_side);
  } else {
    // The frame's cylinder image when the caller has it (the same values as converting here).
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

// The colour overlap an appearance match needs besides its score: the correlation alone
// may follow an occluder or the background that took the target's place.
constexpr double kMinAppearanceOverlap = 0.1;

}  // namespace

int TrackerOptions::EpsilonPixels(int width) const {
  return std::max(1, static_cast<int>(std::lround(epsilon * width / 128.0)));
}

int TrackerOptions::EpsilonMaxPixels(int width) const {
  return std::max(EpsilonPixels(width), static_cast<int>(std::lround(epsilon_max * width / 128.0)));
}

namespace {

constexpr EnumTable<TrackerMode, 2> kTrackerModes = {{{
    {TrackerMode::kThesis, "thesis"},
    {TrackerMode::kBounded, "bounded"},
}}};

}  // namespace

const OptionFields<TrackerOptions>& TrackerOptions::Fields() {
  using O = TrackerOptions;
  static const OptionFields<TrackerOptions> fields = {
      {"mode", EnumField<&O::mode, kTrackerModes>(),
       "thesis: chapter 4 as written; bounded: refinement and box bounded (docs/TRACKING.md)"},
      {"t_colour", &O::t_colour, Range::Closed(0.001, 1000),
       "T_c: a template vertex matches a ROI vertex below this colour distance"},
      {"t_oversegment", &O::t_oversegment, Range::Closed(0.001, 1000),
       "T_co: T_max of the ROI's over-segmentation"},
      {"t_refine", &O::t_refine, Range::Closed(0, 1000),
       "T_cr: colour threshold of the target refinement"},
      {"alpha", &O::alpha, Range::Closed(0.001, 1), "forgetting constant of the template weights"},
      {"epsilon", &O::epsilon, Range::Closed(0, 1000),
       "ROI border, px at a width of 128 (scaled with the width)"},
      {"epsilon_max", &O::epsilon_max, Range::Closed(0, 1000),
       "the ROI border's maximum while the target is not found"},
      {"working_area", &O::working_area, Range::Closed(0.01, 1),
       "T_A: share of the template's area at the working level"},
      {"min_overlap", &O::min_overlap, Range::Closed(0.01, 1),
       "thesis: the weighted overlap that accepts a displacement"},
      {"bounded_min_overlap", &O::bounded_min_overlap, Range::Closed(0.01, 1),
       "bounded: the same, without appearance"},
      {"bound_growth", &O::bound_growth, Range::Closed(0, 1),
       "bounded: the target grows by at most this share of its box a frame, each side"},
      {"size_rate", &O::size_rate, Range::Closed(0, 1),
       "bounded: the box's size follows the mask's box by this share a frame"},
      {"centre_rate", &O::centre_rate, Range::Closed(0, 1),
       "bounded: the box's centre follows the mask's box by this share a frame"},
      {"distinctive_weights", &O::distinctive_weights,
       "bounded: template weights scaled by how distinctive their colour is"},
      {"distinct_rate", &O::distinct_rate, Range::Closed(0, 1),
       "bounded: the distinctiveness table's update rate; 0: the first frame's"},
      {"motion_sigma", &O::motion_sigma, Range::Closed(0, 100),
       "bounded: the motion prior's sigma, box sides; 0: off"},
      {"appearance", &O::appearance, "bounded: match the target's grey appearance too (ZNCC)"},
      {"appearance_share", &O::appearance_share, Range::Closed(0, 1),
       "bounded: the appearance's share of a displacement's score"},
      {"appearance_rate", &O::appearance_rate, Range::Closed(0, 1),
       "bounded: the appearance model's update rate"},
      {"min_score", &O::min_score, Range::Closed(0.01, 1),
       "bounded: the score that accepts a displacement, with appearance"},
      {"redetect_range", &O::redetect_range, Range::Closed(0, 10),
       "bounded: a target not found is searched for within this many box sides"},
      {"redetect_ratio", &O::redetect_ratio, Range::Closed(0.01, 1),
       "bounded: ... and moves where it matches by this share of its typical correlation"},
      {"occlusion", &O::occlusion,
       "bounded: the occlusion rules (occlusion_gate, occlusion_ratio, occlusion_alpha)"},
      {"occlusion_gate", &O::occlusion_gate, Range::Closed(0, 1),
       "bounded: a match under this share of the typical correlation teaches nothing; 0: off"},
      {"occlusion_ratio", &O::occlusion_ratio, Range::Closed(0, 1),
       "bounded: a match under this share of the typical correlation is an occlusion; 0: off"},
      {"occlusion_alpha", &O::occlusion_alpha, Range::Closed(0.001, 1),
       "bounded: the template's forgetting constant while a target with appearance is missed"},
      CodeOnly<O>({"pyramid_parts", &O::pyramid_parts,
                   "the ROIs' pyramid built in parts (true) or whole; the same results"})};
  return fields;
}

std::string TrackerOptions::Check() const {
  const std::string error = CheckFieldRanges(*this, Fields());
  if (!error.empty()) return error;
  if (!(epsilon_max >= epsilon)) return "epsilon_max must be >= epsilon";
  return "";
}

const char* TrackerModeName(TrackerMode mode) { return kTrackerModes.Name(mode); }

const std::vector<std::string>& TrackerModeNames() {
  static const std::vector<std::string> names = kTrackerModes.Names();
  return names;
}

bool TrackerModeFromName(std::string_view name, TrackerMode* mode) {
  return kTrackerModes.FromName(name, mode);
}

const char* TrackStateName(TrackState state) {
  switch (state) {
    case TrackState::kFound:
      return "found";
    case TrackState::kOccluded:
      return "occluded";
    case TrackState::kLost:
      return "lost";
  }
  return "lost";
}

void MultiTracker::Impl::Merge(size_t a, size_t b, std::vector<cv::Rect>* groups,
                               std::vector<cv::Rect>* spans) {
  (*groups)[a] = Aligned((*groups)[a] | (*groups)[b]);
  (*spans)[a] |= (*spans)[b];
  groups->erase(groups->begin() + static_cast<std::ptrdiff_t>(b));
  spans->erase(spans->begin() + static_cast<std::ptrdiff_t>(b));
  for (int& g : group_of) {
    if (g == static_cast<int>(b)) {
      g = static_cast<int>(a);
    } else if (g > static_cast<int>(b)) {
      --g;
    }
  }
}

void MultiTracker::Impl::ReleasePyramids() {
  for (auto& pool : hierarchies) {
    for (auto& h : pool) h->Release();
  }
}

Hierarchy& MultiTracker::Impl::Pyramid(TrackSimilarity similarity, size_t index) {
  auto& pool = hierarchies[similarity == TrackSimilarity::kSkin ? 1 : 0];
  while (pool.size() <= index) pool.push_back(std::make_unique<Hierarchy>(this->pool));
  return *pool[index];
}

std::vector<TemplateLevel> MultiTracker::Impl::MakeTemplate(
    const Hierarchy& h, const std::vector<uint8_t>& in_target, const cv::Rect& keep,
    const std::vector<TemplateLevel>* old, cv::Point shift, int pyramid_levels) const {
  const int levels = std::min(pyramid_levels, kMaxTemplateLevel + 1);
  std::vector<TemplateLevel> result(levels);
  for (int l = 0; l < levels; ++l) {
    const bool built = l < h.bip->num_levels();
    // Window: the crop's cells, joined with the shifted old window. Above the part's levels
    // the whole pyramid's cells of the level hold every cell inside `keep` (which lies in
    // the crop), and so does the window.
    cv::Rect window = built ? cv::Rect((h.origin.x >> l), (h.origin.y >> l), h.bip->level(l).cols,
                                       h.bip->level(l).rows)
                            : CellsInside(keep, l);
    if (old != nullptr && l < static_cast<int>(old->size()) && !(*old)[l].cells.empty()) {
      cv::Rect moved = (*old)[l].cells;
      moved.x += static_cast<int>(std::lround(shift.x / static_cast<double>(1 << l)));
      moved.y += static_cast<int>(std::lround(shift.y / static_cast<double>(1 << l)));
      window |= moved;
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
      const int dx = static_cast<int>(std::lround(shift.x / static_cast<double>(1 << l)));
      const int dy = static_cast<int>(std::lround(shift.y / static_cast<double>(1 << l)));
      for (int y = o.cells.y; y < o.cells.y + o.cells.height; ++y) {
        for (int x = o.cells.x; x < o.cells.x + o.cells.width; ++x) {
          const size_t i = o.Index(x, y);
          const float w = o.weight[i] - options.alpha;
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

int MultiTracker::Impl::WorkingLevel(const Target& target) const {
  if (target.levels.empty()) return -1;
  const double base = target.levels[0].TotalArea();
  int working = 0;
  for (int l = 1; l < static_cast<int>(target.levels.size()); ++l) {
    if (base > 0 && target.levels[l].TotalArea() > options.working_area * base) working = l;
  }
  return working;
}

void MultiTracker::Impl::PaintTarget(const Hierarchy& h, const std::vector<uint8_t>& in_target,
                                     const cv::Rect& roi, cv::Size frame_size,
                                     cv::Mat* mask) const {
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

MultiTracker::Impl::Match MultiTracker::Impl::Localise(const Target& target, const Hierarchy& h,
                                                       std::vector<uint8_t>* in_target) {
  correlated_ = Correlate(target, target.roi, &correlation_);
  box_to_roi_ = target.box.tl() - target.roi.tl();
  for (int l = std::min(WorkingLevel(target), h.bip->num_levels() - 1); l >= 0; --l) {
    Match match;
    const double min_overlap =
        options.mode == TrackerMode::kBounded ? options.bounded_min_overlap : options.min_overlap;
    if (!SearchLevel(target, h, l, nullptr, min_overlap, &match)) continue;
    if (options.mode == TrackerMode::kBounded && l > 0) {
      const int cell = 1 << l;
      const cv::Rect window(match.displacement.x * cell - cell, match.displacement.y * cell - cell,
                            2 * cell + 1, 2 * cell + 1);
      Match fine;
      if (SearchLevel(target, h, 0, &window, 0.0, &fine)) match = fine;
    }
    MarkMatched(target, h, match, in_target);
    return match;
  }
  return {};
}

// Longer than most on purpose: the tracker's inner loop (4.2.3), the displacement scan and its
// early exits on one set of loaded planes; split, the hot loop would pass its state through
// arguments (docs/PERFORMANCE.md times it).
bool MultiTracker::Impl::SearchLevel(const Target& target, const Hierarchy& h, int l,
                                     const cv::Rect* window, double min_overlap, Match* match) {
  const float t2 = options.t_colour * options.t_colour;
  const TemplateLevel& t = target.levels[l];
  const BipLevel& level = h.bip->level(l);
  const cv::Rect roi = CellsInside(target.roi, l);
  const int ox = h.origin.x >> l, oy = h.origin.y >> l;
  search_.Load(t, level, roi, ox, oy, target.distinct);
  if (search_.total <= 0) return false;
  const cv::Rect& occupied = search_.occupied;
  // Displacements that keep the occupied cells inside the ROI, nearest to the previous
  // motion first, so that among equal overlaps the nearest wins by coming first.
  int dx0 = roi.x - occupied.x, dx1 = roi.x + roi.width - (occupied.x + occupied.width);
  int dy0 = roi.y - occupied.y, dy1 = roi.y + roi.height - (occupied.y + occupied.height);
  if (window != nullptr) {
    dx0 = std::max(dx0, window->x), dx1 = std::min(dx1, window->x + window->width - 1);
    dy0 = std::max(dy0, window->y), dy1 = std::min(dy1, window->y + window->height - 1);
  }
  if (dx1 < dx0 || dy1 < dy0) return false;
  const cv::Point prior(
      static_cast<int>(std::lround(target.motion.x / static_cast<double>(1 << l))),
      static_cast<int>(std::lround(target.motion.y / static_cast<double>(1 << l))));
  const std::vector<cv::Point>& displacements = search_.Order(dx0, dx1, dy0, dy1, prior);
  // The smallest weight sum that is accepted (overlap > min_overlap).
  const int64_t total = search_.total;
  int64_t accepted = static_cast<int64_t>(std::floor(min_overlap * total));
  while (accepted > 0 && static_cast<double>(accepted) / total > min_overlap) --accepted;
  while (static_cast<double>(accepted) / total <= min_overlap) ++accepted;
  // Every displacement is scored, row by row of the template; one stops being scored as
  // soon as the weight it has missed shows that it can neither be accepted nor beat the
  // best so far. The accepted result is that of the exhaustive search, ties included.
  int64_t best = accepted - 1;
  cv::Point best_d;
  bool found = false;
  const int width = occupied.width;
  // The overlap of displacement d (PlacedOverlap: exact when above `bar`).
  auto score_at = [&](const cv::Point& d, int64_t bar) {
    const size_t from =
        static_cast<size_t>(occupied.y + d.y - roi.y) * roi.width + (occupied.x + d.x - roi.x);
    return PlacedOverlap(search_.colour[0].data(), search_.colour[1].data(),
                         search_.colour[2].data(), search_.weight.data(), width, occupied.height,
                         &search_.roi[0][from], &search_.roi[1][from], &search_.roi[2][from],
                         roi.width, t2, total, bar);
  };
  if (correlated_) {
    // The appearance joins the overlap (TrackerOptions::appearance). The score is not
    // monotone in the search order, so every displacement is scored exactly.
    const double sigma = std::max(
        1.0, options.motion_sigma * std::sqrt(static_cast<double>(target.box.area())) / (1 << l));
    const double share = options.appearance_share;
    double best_score = 0.0;
    for (const cv::Point& d : displacements) {
      const double ex = d.x - prior.x, ey = d.y - prior.y;
      const double k =
          options.motion_sigma > 0.f ? std::exp(-(ex * ex + ey * ey) / (2 * sigma * sigma)) : 1.0;
      if (k <= best_score) break;  // nearest first: k only falls
      const double c = std::max(0.0, CorrelationAt(d, l));
      const int64_t overlap = score_at(d, -1);
      const double score = k * ((1 - share) * static_cast<double>(overlap) / total + share * c);
      if (score > best_score) {
        best_score = score;
        best = overlap;
        best_d = d;
        best_correlation_ = c;
      }
    }
    // The prior-weighted score is the one accepted: a far displacement needs a strong match.
    // The correlation alone may follow an occluder or the background that took the
    // target's place, so some colour overlap is needed too.
    found = best_score > options.min_score &&
            static_cast<double>(best) / total >= kMinAppearanceOverlap;
  } else if (options.mode == TrackerMode::kBounded && options.motion_sigma > 0.f) {
    // The bounded mode weighs each accepted overlap by a Gaussian of the displacement's
    // distance to the previous motion, of `motion_sigma` times the box's mean side: among
    // displacements that match, the target most likely moved little. Displacements come
    // nearest first, so the weight only falls, and the search stops once even a whole
    // overlap could no longer win.
    const double sigma = std::max(
        1.0, options.motion_sigma * std::sqrt(static_cast<double>(target.box.area())) / (1 << l));
    double best_weighted = 0.0;
    for (const cv::Point& d : displacements) {
      const double ex = d.x - prior.x, ey = d.y - prior.y;
      const double k = std::exp(-(ex * ex + ey * ey) / (2 * sigma * sigma));
      if (found && k * total <= best_weighted) break;
      const int64_t bar = std::max<int64_t>(
          accepted - 1, found ? static_cast<int64_t>(std::floor(best_weighted / k)) : 0);
      const int64_t score = score_at(d, bar);
      if (score > bar && k * score > best_weighted) {
        best_weighted = k * score;
        best = score;
        best_d = d;
        found = true;
      }
    }
  } else {
    for (const cv::Point& d : displacements) {
      const int64_t score = score_at(d, best);
      if (score > best) {
        best = score;
        best_d = d;
        found = true;
      }
    }
  }
  if (!found) return false;
  *match = {true, l, best_d, static_cast<double>(best) / total};
  return true;
}

void MultiTracker::Impl::MarkMatched(const Target& target, const Hierarchy& h, const Match& match,
                                     std::vector<uint8_t>* in_target) const {
  const float t2 = options.t_colour * options.t_colour;
  const int l = match.level;
  const TemplateLevel& t = target.levels[l];
  const BipLevel& level = h.bip->level(l);
  for (int y = t.cells.y; y < t.cells.y + t.cells.height; ++y) {
    for (int x = t.cells.x; x < t.cells.x + t.cells.width; ++x) {
      const size_t i = t.Index(x, y);
      if (t.weight[i] <= 0.f) continue;
      const int cell = h.Cell(l, x + match.displacement.x, y + match.displacement.y);
      if (cell < 0 || !level.hom[cell] ||
          SquaredDistance(&t.colour[3 * i], level.Feature(cell)) >= t2) {
        continue;
      }
      const int r = h.region[l][cell];
      if (r >= 0) (*in_target)[r] = 1;
    }
  }
}

void MultiTracker::Impl::Refine(const Hierarchy& h, const cv::Rect& roi,
                                std::vector<uint8_t>* in_target) const {
  const std::vector<uint8_t> first = *in_target;
  const float t2 = options.t_refine * options.t_refine;
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

void MultiTracker::Impl::Track(const cv::Mat& frame, const cv::Mat& skin, const cv::Mat& cylinder,
                               std::vector<TrackResult>* results) {
  segmentation_ms = 0.0;
  if (options.mode == TrackerMode::kBounded && options.appearance) {
    cv::cvtColor(frame, grey_, cv::COLOR_BGR2GRAY);
    frame_ = frame;
    frame_cylinder_ = cylinder;
  }
  const cv::Rect image(0, 0, frame.cols, frame.rows);
  for (const TrackSimilarity similarity : {TrackSimilarity::kColour, TrackSimilarity::kSkin}) {
    int pyramid_levels = 0;
    if (!BuildPyramids(frame, skin, cylinder, similarity, &pyramid_levels)) continue;
    for (size_t i = 0; i < targets.size(); ++i) {
      if (targets[i].similarity != similarity) continue;
      results->push_back(TrackTarget(i, frame, pyramid_levels));
    }
  }
  std::sort(results->begin(), results->end(),
            [](const TrackResult& a, const TrackResult& b) { return a.id < b.id; });
  ReleasePyramids();
  targets.erase(std::remove_if(targets.begin(), targets.end(),
                               [](const Target& t) { return t.levels.empty(); }),
                targets.end());
}

bool MultiTracker::Impl::BuildPyramids(const cv::Mat& frame, const cv::Mat& skin,
                                       const cv::Mat& cylinder, TrackSimilarity similarity,
                                       int* pyramid_levels) {
  const cv::Rect image(0, 0, frame.cols, frame.rows);
  // One pyramid over the union of this similarity's ROIs (4.3).
  union_mask.create(frame.size(), CV_8UC1);
  union_mask.setTo(0);
  bool any = false;
  cv::Rect bounds;
  for (Target& target : targets) {
    if (target.similarity != similarity) continue;
    target.roi =
        cv::Rect(target.box.x - target.border, target.box.y - target.border,
                 target.box.width + 2 * target.border, target.box.height + 2 * target.border) &
        image;
    if (target.roi.empty()) continue;
    union_mask(target.roi).setTo(255);
    bounds = any ? bounds | target.roi : target.roi;
    any = true;
  }
  if (!any) return false;
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
  group_of.assign(targets.size(), -1);
  for (size_t i = 0; i < targets.size(); ++i) {
    if (targets[i].similarity != similarity || targets[i].roi.empty()) continue;
    group_of[i] = static_cast<int>(groups.size());
    groups.push_back(Aligned(targets[i].roi));
    spans.push_back(targets[i].roi);
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
      !options.pyramid_parts || std::any_of(spans.begin(), spans.end(), [](const cv::Rect& span) {
        return span.width >= kUnaligned && span.height >= kUnaligned;
      });
  while (whole_pyramid && groups.size() > 1) Merge(0, 1, &groups, &spans);
  const cv::Rect whole = Aligned(bounds);
  const int schedule_side = std::min(whole.width, whole.height);
  const Stopwatch segmentation;
  for (size_t g = 0; g < groups.size(); ++g) {
    Hierarchy& part = Pyramid(similarity, g);
    BuildHierarchy(frame, skin, similarity, union_mask, groups[g], schedule_side,
                   options.t_oversegment, &part, cylinder);
    *pyramid_levels = std::max(*pyramid_levels, part.bip->num_levels());
  }
  segmentation_ms += segmentation.ElapsedMs();
  return true;
}

TrackResult MultiTracker::Impl::TrackTarget(size_t i, const cv::Mat& frame, int pyramid_levels) {
  Target& target = targets[i];
  // A target with an empty ROI (outside the image) is searched in no pyramid.
  const Hierarchy& h = Pyramid(target.similarity, std::max(group_of[i], 0));
  TrackResult result;
  result.id = target.id;
  result.roi = target.roi;
  std::vector<uint8_t> in_target(h.regions, 0);
  const Match match = group_of[i] < 0 ? Match() : Localise(target, h, &in_target);
  result.overlap = match.overlap;
  // Bounded mode with an appearance model: a match whose correlation falls well under the
  // target's typical one is an occluder or the background taking the target's place.
  const double typical = target.typical_correlation;
  const bool judged = options.mode == TrackerMode::kBounded && options.occlusion &&
                      match.found && correlated_ && typical > 0.0;
  const bool occluded = judged && best_correlation_ < options.occlusion_ratio * typical;
  if (occluded) {
    Missed(frame, &target, &result);
  } else if (match.found) {
    // Under occlusion_gate the box moves, but the target learns nothing of the place.
    const bool learn = !(judged && best_correlation_ < options.occlusion_gate * typical);
    Found(h, match, frame, pyramid_levels, learn, &in_target, &target, &result);
  } else {
    Missed(frame, &target, &result);
  }
  result.box = target.box;
  result.centroid = target.centroid;
  return result;
}

void MultiTracker::Impl::Found(const Hierarchy& h, const Match& match, const cv::Mat& frame,
                               int pyramid_levels, bool learn,
                               std::vector<uint8_t>* in_target_pointer,
                               Target* target_pointer, TrackResult* result) {
  Target& target = *target_pointer;
  std::vector<uint8_t>& in_target = *in_target_pointer;
  const cv::Rect image(0, 0, frame.cols, frame.rows);
  const cv::Point shift(match.displacement.x << match.level, match.displacement.y << match.level);
  cv::Rect keep = target.roi;
  if (options.mode == TrackerMode::kBounded) {
    // The target's box first, then its pixels and template inside that box only.
    const cv::Rect plausible = BoundTarget(h, target, shift, image, &in_target);
    PaintTarget(h, in_target, plausible, frame.size(), &target.mask);
    const cv::Rect mask_box = cv::boundingRect(target.mask(plausible)) + plausible.tl();
    if (!mask_box.empty()) {
      cv::Rect2d smooth;
      keep = SmoothBox(target, shift, mask_box, plausible, image, &smooth);
      target.smooth = smooth;
      target.box = keep;
    }
  } else {
    Refine(h, target.roi, &in_target);
  }
  PaintTarget(h, in_target, keep, frame.size(), &target.mask);
  target.levels = MakeTemplate(h, in_target, keep, &target.levels, shift, pyramid_levels);
  // The target's pixels all lie in its ROI.
  const cv::Mat inside = target.mask(target.roi);
  const cv::Moments moments = cv::moments(inside, true);
  if (moments.m00 > 0) {
    if (options.mode == TrackerMode::kThesis) {
      target.box = cv::boundingRect(inside) + target.roi.tl();
    }
    target.centroid = {static_cast<float>(target.roi.x + moments.m10 / moments.m00),
                       static_cast<float>(target.roi.y + moments.m01 / moments.m00)};
  }
  target.motion = shift;
  target.border = options.EpsilonPixels(frame.cols);
  if (options.mode == TrackerMode::kBounded && learn) {
    LearnDistinct(h, &target);
    LearnAppearance(&target);
    if (correlated_) {
      target.typical_correlation = target.typical_correlation == 0.0
                                       ? best_correlation_
                                       : 0.9 * target.typical_correlation + 0.1 * best_correlation_;
      const double distinct = MeanDistinct(target, target.box);
      if (distinct >= 0.0) {
        target.typical_distinct = target.typical_distinct == 0.0
                                      ? distinct
                                      : 0.9 * target.typical_distinct + 0.1 * distinct;
      }
    }
  }
  result->state = TrackState::kFound;
  result->level = match.level;
  result->area = static_cast<int>(moments.m00);
}

void MultiTracker::Impl::Missed(const cv::Mat& frame, Target* target_pointer, TrackResult* result) {
  Target& target = *target_pointer;
  const int epsilon_max = options.EpsilonMaxPixels(frame.cols);
  // Every weight decays, the ROI border grows.
  target.mask.release();
  // A weight left at a rounding error of 0 (1 - k alpha in float) is 0, as in
  // MakeTemplate: the target is lost after 1 / alpha frames, not one more.
  // A bounded target with an appearance model forgets at occlusion_alpha: it outlasts an
  // occlusion longer, and its model can find it again when it comes out (Redetect).
  const float alpha = options.mode == TrackerMode::kBounded && options.occlusion &&
                              options.appearance && !target.appearance.empty()
                          ? options.occlusion_alpha
                          : options.alpha;
  for (TemplateLevel& level : target.levels) {
    for (float& w : level.weight) w = w - alpha > 1e-6f ? w - alpha : 0.f;
  }
  while (!target.levels.empty() && target.levels.back().Empty()) target.levels.pop_back();
  target.border = std::min(target.border + 1, epsilon_max);
  target.motion = {0, 0};
  if (!target.levels.empty()) Redetect(&target);
  result->state = target.levels.empty() ? TrackState::kLost : TrackState::kOccluded;
}

int MultiTracker::Impl::Start(const cv::Mat& frame, const cv::Mat& skin, TrackSimilarity similarity,
                              const cv::Mat& target_mask, const cv::Mat& build_mask) {
  if (cv::countNonZero(target_mask) == 0) return -1;
  Hierarchy& h = Pyramid(similarity, 0);
  BuildHierarchy(frame, skin, similarity, build_mask, cv::boundingRect(build_mask), 0,
                 options.t_oversegment, &h);
  // The target's regions: those with most of their pixels in `target_mask`.
  std::vector<int> inside(h.regions, 0), all(h.regions, 0);
  const BipLevel& base = h.bip->level(0);
  for (int y = 0; y < h.size.height; ++y) {
    const uchar* m = target_mask.ptr<uchar>(y + h.origin.y) + h.origin.x;
    for (int x = 0; x < h.size.width; ++x) {
      const int cell = y * base.cols + x;
      if (!base.hom[cell] || h.region[0][cell] < 0) continue;
      ++all[h.region[0][cell]];
      if (m[x]) ++inside[h.region[0][cell]];
    }
  }
  std::vector<uint8_t> in_target(h.regions, 0);
  for (int r = 0; r < h.regions; ++r) in_target[r] = 2 * inside[r] > all[r];
  Target target;
  target.similarity = similarity;
  // The bounded mode keeps the target inside the mask's box: an over-segmentation region
  // mostly in the mask may still reach far beyond it.
  const cv::Rect keep = options.mode == TrackerMode::kBounded
                            ? cv::boundingRect(target_mask)
                            : cv::Rect(0, 0, frame.cols, frame.rows);
  PaintTarget(h, in_target, keep, frame.size(), &target.mask);
  if (cv::countNonZero(target.mask) == 0) {
    h.Release();
    return -1;
  }
  target.levels = MakeTemplate(h, in_target, keep, nullptr, {}, h.bip->num_levels());
  if (target.levels.empty()) {
    h.Release();
    return -1;
  }
  const cv::Moments moments = cv::moments(target.mask, true);
  target.box = cv::boundingRect(target.mask);
  target.centroid = {static_cast<float>(moments.m10 / moments.m00),
                     static_cast<float>(moments.m01 / moments.m00)};
  target.border = options.EpsilonPixels(frame.cols);
  if (options.mode == TrackerMode::kBounded && similarity == TrackSimilarity::kColour) {
    target.roi = cv::boundingRect(build_mask);
    LearnDistinct(h, &target);
    if (options.appearance) {
      cv::cvtColor(frame, grey_, cv::COLOR_BGR2GRAY);
      LearnAppearance(&target);
    }
  }
  h.Release();
  target.id = next_id++;
  targets.push_back(std::move(target));
  return targets.back().id;
}

MultiTracker::MultiTracker(TrackerOptions options, BipPool* pool)
    : options_(options), impl_(std::make_unique<Impl>(options, pool)) {
  const std::string error = options_.Check();
  if (!error.empty()) throw ConfigError("tracker: " + error);
}

MultiTracker::~MultiTracker() = default;

namespace {

void CheckFrame(const cv::Mat& frame, TrackSimilarity similarity, const cv::Mat& skin) {
  ATTEND_CHECK(!frame.empty() && frame.type() == CV_8UC3) << "frames must be 8-bit BGR";
  if (similarity == TrackSimilarity::kSkin) {
    ATTEND_CHECK(skin.type() == CV_8UC1 && skin.size() == frame.size())
        << "skin targets need the frame's binary skin map";
  }
}

}  // namespace

int MultiTracker::StartFromMask(const cv::Mat& frame, const cv::Mat& mask,
                                TrackSimilarity similarity, const cv::Mat& skin) {
  CheckFrame(frame, similarity, skin);
  ATTEND_CHECK(mask.type() == CV_8UC1 && mask.size() == frame.size())
      << "a target mask must be CV_8UC1 of the frame's size";
  // Over-segment the mask's box plus the ROI border, so that regions can be judged by how much
  // of them lies in the mask.
  const int border = options_.EpsilonPixels(frame.cols);
  const cv::Rect box = cv::boundingRect(mask);
  if (box.empty()) return -1;
  cv::Mat build(frame.size(), CV_8UC1, cv::Scalar(0));
  build(cv::Rect(box.x - border, box.y - border, box.width + 2 * border, box.height + 2 * border) &
        cv::Rect(0, 0, frame.cols, frame.rows))
      .setTo(255);
  return impl_->Start(frame, skin, similarity, mask, build);
}

int MultiTracker::StartFromBox(const cv::Mat& frame, const cv::Rect& box,
                               TrackSimilarity similarity, const cv::Mat& skin) {
  CheckFrame(frame, similarity, skin);
  const cv::Rect image(0, 0, frame.cols, frame.rows);
  const cv::Rect inside = box & image;
  if (inside.empty()) return -1;
  cv::Mat mask(frame.size(), CV_8UC1, cv::Scalar(0));
  if (options_.mode == TrackerMode::kBounded && similarity == TrackSimilarity::kColour) {
    // The box is the target: a user's box says where the object is, and a multi-coloured
    // object's parts need not be regions that lie mostly inside it.
    mask(inside).setTo(255);
    const int id = StartFromMask(frame, mask, similarity, skin);
    if (id >= 0) impl_->targets.back().box = inside;
    return id;
  }
  if (similarity == TrackSimilarity::kSkin) {
    mask(inside).setTo(255, skin(inside));
    return StartFromMask(frame, mask, similarity, skin);
  }
  // The target is what the colour segmentation (thesis 4.2.1, chapter 3) finds mostly inside
  // the box. The box's surroundings, as wide as the box, are segmented with it, so that the
  // background in the box's corners joins the background outside and stays out.
  const cv::Rect context = cv::Rect(inside.x - inside.width, inside.y - inside.height,
                                    3 * inside.width, 3 * inside.height) &
                           image;
  Segmentation segmentation;
  impl_->segmenter.Segment(frame(context), &segmentation);
  impl_->segmenter.ReleasePyramid();
  const cv::Rect local = inside - context.tl();
  std::vector<int> within(segmentation.regions.size(), 0);
  for (int y = local.y; y < local.y + local.height; ++y) {
    const int* label = segmentation.labels.ptr<int>(y);
    for (int x = local.x; x < local.x + local.width; ++x) {
      if (label[x] >= 0) ++within[label[x]];
    }
  }
  for (int y = 0; y < context.height; ++y) {
    const int* label = segmentation.labels.ptr<int>(y);
    uchar* out = mask.ptr<uchar>(y + context.y) + context.x;
    for (int x = 0; x < context.width; ++x) {
      if (label[x] >= 0 && 2 * within[label[x]] > segmentation.regions[label[x]].area) out[x] = 255;
    }
  }
  return StartFromMask(frame, mask, similarity, skin);
}

int MultiTracker::StartFromRegion(const cv::Mat& frame, const cv::Mat& labels, int region,
                                  TrackSimilarity similarity, const cv::Mat& skin) {
  CheckFrame(frame, similarity, skin);
  ATTEND_CHECK(labels.type() == CV_32SC1 && labels.size() == frame.size())
      << "segmentation labels must be CV_32SC1 of the frame's size";
  if (region < 0) return -1;
  return StartFromMask(frame, labels == region, similarity, skin);
}

void MultiTracker::Track(const cv::Mat& frame, std::vector<TrackResult>* results,
                         const cv::Mat& skin, const cv::Mat& cylinder) {
  const Stopwatch stopwatch;
  ATTEND_CHECK(!frame.empty() && frame.type() == CV_8UC3) << "frames must be 8-bit BGR";
  ATTEND_CHECK(cylinder.empty() || (cylinder.type() == CV_32FC3 && cylinder.size() == frame.size()))
      << "the cylinder image must be CV_32FC3 of the frame's size";
  std::vector<TrackResult> found;
  impl_->Track(frame, skin, cylinder, &found);
  results->insert(results->end(), found.begin(), found.end());
  milliseconds_ = stopwatch.ElapsedMs();
  segmentation_milliseconds_ = impl_->segmentation_ms;
}

cv::Mat MultiTracker::Mask(int id) const {
  for (const Impl::Target& target : impl_->targets) {
    if (target.id == id) return target.mask;
  }
  return cv::Mat();
}

cv::Mat MultiTracker::TemplateWeights(int id, int level) const {
  for (const Impl::Target& target : impl_->targets) {
    if (target.id != id) continue;
    if (level < 0 || level >= static_cast<int>(target.levels.size())) return cv::Mat();
    const TemplateLevel& t = target.levels[level];
    return cv::Mat(t.cells.height, t.cells.width, CV_32FC1, const_cast<float*>(t.weight.data()))
        .clone();
  }
  return cv::Mat();
}

void MultiTracker::Remove(int id) {
  auto& targets = impl_->targets;
  targets.erase(std::remove_if(targets.begin(), targets.end(),
                               [id](const Impl::Target& t) { return t.id == id; }),
                targets.end());
}

std::vector<int> MultiTracker::ids() const {
  std::vector<int> ids;
  for (const Impl::Target& target : impl_->targets) ids.push_back(target.id);
  return ids;
}

}  // namespace attend
