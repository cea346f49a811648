// MultiTracker's implementation (tracker/tracker.h), shared by its two files: tracker.cc holds
// the thesis's tracker (chapter 4: the template 4.2.1, the ROIs and their pyramid 4.3, the
// top-down localisation 4.2.3, the refinement 4.2.4 and the template update 4.2.5-4.2.7) and
// bounded_mode.cc what TrackerMode::kBounded adds to it (docs/TRACKING.md, "Modes"): the
// plausible box, the smoothed box, the distinctive colour weights and the grey appearance
// with its redetection. Not part of the API.
#pragma once

#include <algorithm>
#include <cstdint>
#include <limits>
#include <memory>
#include <opencv2/core.hpp>
#include <vector>

#include "pyramid/bip.h"
#include "pyramid/segmentation.h"
#include "tracker/tracker.h"

namespace attend {
namespace tracker_internal {

// Pyramids are built over a crop of the frame whose origin is a multiple of this, so that a
// cell of level l <= kMaxTemplateLevel has the same absolute position in every frame.
inline constexpr int kMaxTemplateLevel = 6;
inline constexpr int kAlignment = 1 << kMaxTemplateLevel;

// One level of a template: a window of absolute cells with each vertex's colour, area and
// weight (weight 0: no vertex).
struct TemplateLevel {
  cv::Rect cells;  // absolute cell coordinates of the window
  std::vector<float> colour;
  std::vector<int> area;
  std::vector<float> weight;

  size_t Index(int x, int y) const {
    return static_cast<size_t>(y - cells.y) * cells.width + (x - cells.x);
  }
  double TotalArea() const {
    double total = 0.0;
    for (size_t i = 0; i < weight.size(); ++i) total += weight[i] > 0.f ? area[i] : 0;
    return total;
  }
  bool Empty() const {
    return std::none_of(weight.begin(), weight.end(), [](float w) { return w > 0.f; });
  }
};

// A pyramid built over a crop of the frame, with the region (root) of every vertex.
struct Hierarchy {
  cv::Point origin;  // the crop's top-left pixel in the frame, a multiple of kAlignment
  cv::Size size;
  BipBuilder builder;
  const Bip* bip = nullptr;
  explicit Hierarchy(BipPool* pool) : builder(BipOptions{}, pool) {}
  std::vector<std::vector<int32_t>> region;  // per level, per vertex id: root index, -1 none
  int regions = 0;

  // Gives the pyramid's buffers back to the pool (pyramid/bip.h) once the frame is done with
  // it; the region labels are kept, to be refilled by the next frame.
  void Release() {
    builder.Release();
    bip = nullptr;
  }
  // Region of every vertex, from the top level down.
  void LabelRegions() {
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
  // The cell of level l at absolute cell (x, y), or -1 outside the crop.
  int Cell(int l, int x, int y) const {
    const BipLevel& level = bip->level(l);
    const int cx = x - (origin.x >> l), cy = y - (origin.y >> l);
    if (cx < 0 || cy < 0 || cx >= level.cols || cy >= level.rows) return -1;
    return cy * level.cols + cx;
  }
};

// The grey standard deviation below which a target's appearance model is taken as flat.
inline constexpr double kMinAppearanceDeviation = 10.0;

// Template weights in the search are fixed point, 1 = kWeightOne, so that sums are exact and
// do not depend on their order.
inline constexpr double kWeightOne = 65536.0;

// Bins of the HSV cylinder for the bounded mode's colour statistics: 32 units a side on each
// axis (S cos H and S sin H in [-255, 255], V in [0, 255]).
inline constexpr int kChromaBins = 16, kValueBins = 8;
inline constexpr int kColourBins = kChromaBins * kChromaBins * kValueBins;
inline int ColourBin(const float* f) {
  const int bx = std::clamp(static_cast<int>((f[0] + 256.f) / 32.f), 0, kChromaBins - 1);
  const int by = std::clamp(static_cast<int>((f[1] + 256.f) / 32.f), 0, kChromaBins - 1);
  const int bv = std::clamp(static_cast<int>(f[2] / 32.f), 0, kValueBins - 1);
  return (bx * kChromaBins + by) * kValueBins + bv;
}

// One level's search data, reused from call to call: the template over its occupied cells and
// the ROI's cells, both as planes of colour components.
struct LevelSearch {
  cv::Rect occupied;  // absolute cells of the template's vertices (weight > 0)
  std::vector<float> colour[3];
  std::vector<int32_t> weight;
  int64_t total = 0;
  std::vector<float> roi[3];  // the ROI cells, row by row; NaN where no regular vertex
  std::vector<cv::Point> displacements;
  std::vector<int> distance;  // per displacement of the range, in scan order
  std::vector<int> bucket;    // counting sort by distance

  // The displacements of [dx0, dx1] x [dy0, dy1] ordered by squared distance to `prior`, those
  // at equal distance in scan order (rows, then columns): a stable counting sort.
  const std::vector<cv::Point>& Order(int dx0, int dx1, int dy0, int dy1, cv::Point prior) {
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

  // `distinct` (bounded mode; may be empty) scales each template weight by how distinctive
  // its colour is of the target against its surroundings (ColourBin()).
  void Load(const TemplateLevel& t, const BipLevel& level, const cv::Rect& roi_cells, int ox,
            int oy, const std::vector<float>& distinct) {
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
        weight[j] = std::max<int32_t>(
            1, static_cast<int32_t>(std::lround(t.weight[i] * scale * kWeightOne)));
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
};

}  // namespace tracker_internal

struct MultiTracker::Impl {
  struct Target {
    int id = 0;
    TrackSimilarity similarity = TrackSimilarity::kColour;
    std::vector<tracker_internal::TemplateLevel> levels;
    cv::Rect box;
    cv::Point2f centroid;
    int border = 0;    // the ROI's border around `box` for the next frame
    cv::Point motion;  // the last displacement found, pixels (d_f of 4.2.3)
    cv::Rect roi;      // the ROI of the current frame
    cv::Mat mask;      // pixels of the last frame; empty when not found
    // Bounded mode: per colour bin, the share of the target's pixels among the target's and
    // its surroundings' (each normalised by its count); empty: every weight counts wholly.
    std::vector<float> distinct;
    // Bounded mode: the box before rounding, so that a size that follows its evidence by a
    // small share a frame can grow (a rounded box would round each small step back).
    cv::Rect2d smooth;
    // Bounded mode with `appearance`: the grey model of the box (CV_32FC1, the first box's
    // size), and the running means of the correlation it had where the target was found.
    cv::Mat appearance;
    bool appearance_judged = false;  // whether the first box was judged for texture
    double typical_correlation = 0.0;
    double typical_distinct = 0.0;  // running mean of MeanDistinct over the found box
  };

  TrackerOptions options;
  std::unique_ptr<BipPool> own_pool;  // when the tracker was given none
  BipPool* pool;                      // of the pyramids and the segmenter
  std::vector<Target> targets;
  int next_id = 1;
  // Pyramids of the current frame, colour and skin: one per group of ROIs (see Track()).
  std::vector<std::unique_ptr<tracker_internal::Hierarchy>> hierarchies[2];
  std::vector<int> group_of;     // per target: its group's pyramid, -1 for an empty ROI
  double segmentation_ms = 0.0;  // of the last Track()
  Segmenter segmenter;           // chooses a target's regions in a box (thesis 4.2.1)
  cv::Mat union_mask;
  tracker_internal::LevelSearch search_;
  // Bounded mode with `appearance`: the frame in grey, and the ZNCC of the searched target's
  // model over its ROI; correlation_(y, x) is that of the box moved by (x, y) - box_to_roi_.
  cv::Mat grey_;
  cv::Mat frame_;           // the current frame (a header), for MeanDistinct
  cv::Mat frame_cylinder_;  // its cylinder image when the caller gave one (a header)
  mutable cv::Mat cylinder_;
  cv::Mat correlation_;
  cv::Point box_to_roi_;
  bool correlated_ = false;
  double best_correlation_ = 0.0;  // at the last accepted displacement
  mutable cv::Mat model_, patch_;
  mutable std::vector<int> region_inside_, region_all_;  // BoundTarget's counts
  mutable std::vector<float> fg_, bg_;                   // LearnDistinct's histograms

  Impl(const TrackerOptions& o, BipPool* p)
      : options(o),
        own_pool(p == nullptr ? std::make_unique<BipPool>() : nullptr),
        pool(p != nullptr ? p : own_pool.get()),
        segmenter(SegmentationOptions{}, pool) {}

  // Joins group b into group a (a < b): their crops and spans, and the targets' group numbers.
  void Merge(size_t a, size_t b, std::vector<cv::Rect>* groups, std::vector<cv::Rect>* spans);

  // Gives every pyramid's levels back to the pool, at the end of a frame's tracking.
  void ReleasePyramids();
  // The `index`-th pyramid of a similarity, made on first use; each keeps its buffers.
  tracker_internal::Hierarchy& Pyramid(TrackSimilarity similarity, size_t index);

  // The template of a target from the regular cells of `hierarchy` in the target's regions.
  // `in_target` says whether a region is the target's; `keep` limits it to a box (absolute
  // pixels). Cells of the old template that the new target does not cover stay with their
  // weight reduced by alpha, shifted by `shift` pixels.
  // `pyramid_levels` is the height of the whole pyramid over the union of the ROIs, of which
  // `h` may be a lower part: above the part's own levels, old cells only move and decay.
  std::vector<tracker_internal::TemplateLevel> MakeTemplate(
      const tracker_internal::Hierarchy& h, const std::vector<uint8_t>& in_target,
      const cv::Rect& keep, const std::vector<tracker_internal::TemplateLevel>* old,
      cv::Point shift, int pyramid_levels) const;

  // The working level (eq. 4.4): the highest level whose template area exceeds T_A of level 0's.
  int WorkingLevel(const Target& target) const;

  // Sets the target's pixels in `mask` (frame size) and its box and centroid from the regions.
  void PaintTarget(const tracker_internal::Hierarchy& h, const std::vector<uint8_t>& in_target,
                   const cv::Rect& roi, cv::Size frame_size, cv::Mat* mask) const;

  struct Match {
    bool found = false;
    int level = -1;
    cv::Point displacement;  // cells of `level`
    double overlap = 0.0;
  };

  // Top-down localisation (4.2.3) of a target in its ROI; marks the matched ROI vertices'
  // regions in `in_target` (the first stage of 4.2.4). In the bounded mode a match at a coarse
  // level is followed by a search at level 0 within one coarse cell of it, so that the motion
  // and the matched vertices are those of level 0 (a coarse cell of 2^l pixels otherwise
  // rounds the motion by up to 2^l pixels).
  Match Localise(const Target& target, const tracker_internal::Hierarchy& h,
                 std::vector<uint8_t>* in_target);

  // Searches level l of the ROI for the template's best displacement (within `window`, in
  // cells of l, when given) whose weighted overlap exceeds `min_overlap`; false when none does.
  bool SearchLevel(const Target& target, const tracker_internal::Hierarchy& h, int l,
                   const cv::Rect* window, double min_overlap, Match* match);

  // The matched ROI vertices' regions are the target (first stage of 4.2.4).
  void MarkMatched(const Target& target, const tracker_internal::Hierarchy& h, const Match& match,
                   std::vector<uint8_t>* in_target) const;

  // Second stage of 4.2.4: the regions of neighbours (regular and virtual) of the target's
  // regular vertices that are within T_cr of them join the target. One pass, over the target
  // as the first stage left it.
  void Refine(const tracker_internal::Hierarchy& h, const cv::Rect& roi,
              std::vector<uint8_t>* in_target) const;

  // Bounded mode: how distinctive each colour is of the target (its mask) against the rest of
  // its ROI outside its box, a histogram likelihood ratio f / (f + b) of the normalised counts,
  // blended into the previous table by `distinct_rate`. Colours the surroundings share count
  // little in the next frame's overlap; colours only the target has count wholly.
  void LearnDistinct(const tracker_internal::Hierarchy& h, Target* target) const;

  // Bounded mode with `appearance`: the ZNCC of the target's grey model, at its box's size,
  // over `area` of the frame; false when there is no model or `area` cannot hold the box.
  bool Correlate(const Target& target, const cv::Rect& area, cv::Mat* correlation) const;

  // The correlation of the box moved by displacement d of level l; 0 where it was not computed.
  double CorrelationAt(const cv::Point& d, int l) const;

  // The mean distinctiveness (the colour table of LearnDistinct) of the frame's pixels in
  // `box`; -1 without a table.
  double MeanDistinct(const Target& target, const cv::Rect& box) const;

  // Bounded mode with `appearance`: the model follows the found box by `appearance_rate`.
  void LearnAppearance(Target* target) const;

  // Bounded mode with `appearance`, a target not found: its model is searched for within
  // `redetect_range` box sides around its box, and where it correlates by `redetect_ratio` of
  // its typical correlation or more, the box and the template move there (the target is
  // still not found in this frame; the next frame's search starts there).
  void Redetect(Target* target);

  // Bounded refinement (TrackerMode::kBounded). The target may only be where the last box,
  // moved by the match, plausibly is now: that box grown by `bound_growth` of its size on each
  // side. Refinement looks only there, and a region (first stage or refinement) belongs to the
  // target only when most of its pixels in the ROI lie in that box: a region that reaches far
  // outside it is background that the over-segmentation joined to the target. Returns the box.
  cv::Rect BoundTarget(const tracker_internal::Hierarchy& h, const Target& target, cv::Point shift,
                       const cv::Rect& image, std::vector<uint8_t>* in_target) const;

  // The bounded mode's box. The mask's box says where the target is, but a side of it that
  // reaches the plausible box's edge is no evidence of growth (the regions may go on beyond
  // it): that side stays where the moved box has it. The box's size and centre then follow
  // that evidence by a share `size_rate` a frame, so that one frame whose segmentation takes
  // too little or too much does not make the box jump.
  cv::Rect SmoothBox(const Target& target, cv::Point shift, cv::Rect mask_box,
                     const cv::Rect& plausible, const cv::Rect& image, cv::Rect2d* smooth) const;

  void Track(const cv::Mat& frame, const cv::Mat& skin, const cv::Mat& cylinder,
             std::vector<TrackResult>* results);

  // The ROIs of this similarity's targets and the pyramid over their union, in parts (4.3);
  // false when no target of it has an ROI in the image. `pyramid_levels`: the tallest part's.
  bool BuildPyramids(const cv::Mat& frame, const cv::Mat& skin, const cv::Mat& cylinder,
                     TrackSimilarity similarity, int* pyramid_levels);

  // Tracks target `i` in its part of the pyramid: found, it takes its new mask, box and
  // template; not found, it decays.
  TrackResult TrackTarget(size_t i, const cv::Mat& frame, int pyramid_levels);

  // A target found at `match`: its mask, box and template (4.2.4-4.2.6; bounded: its box
  // first, then its pixels inside it). Without `learn` (bounded, a match under
  // occlusion_gate) its distinctive colours, appearance and typical correlation stay as they
  // were.
  void Found(const tracker_internal::Hierarchy& h, const Match& match, const cv::Mat& frame,
             int pyramid_levels, bool learn, std::vector<uint8_t>* in_target_pointer,
             Target* target_pointer, TrackResult* result);

  // A target not found (4.2.7).
  void Missed(const cv::Mat& frame, Target* target_pointer, TrackResult* result);

  int Start(const cv::Mat& frame, const cv::Mat& skin, TrackSimilarity similarity,
            const cv::Mat& target_mask, const cv::Mat& build_mask);
};

}  // namespace attend
