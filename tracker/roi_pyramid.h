// The pyramid the tracker searches in (thesis 4.3): every frame, one BIP over the union of the
// targets' regions of interest (ROIs) with a small T_max (an over-segmentation, 4.2.2), built
// in independent parts, one per group of nearby ROIs. Not part of the API.
#pragma once

#include <cstdint>
#include <memory>
#include <opencv2/core.hpp>
#include <vector>

#include "pyramid/bip.h"
#include "tracker/tracker_options.h"

namespace attend {
namespace tracker_internal {

// Pyramids are built over a crop of the frame whose origin is a multiple of this, so that a
// cell of level l <= kMaxTemplateLevel has the same absolute position in every frame.
inline constexpr int kMaxTemplateLevel = 6;
inline constexpr int kAlignment = 1 << kMaxTemplateLevel;

// A pyramid built over a crop of the frame, with the region (root) of every vertex.
struct Hierarchy {
  cv::Point origin;  // the crop's top-left pixel in the frame, a multiple of kAlignment
  cv::Size size;
  explicit Hierarchy(BipPool* pool) : builder(BipOptions{}, pool) {}

  BipBuilder builder;
  const Bip* bip = nullptr;
  std::vector<std::vector<int32_t>> region;  // per level, per vertex id: root index, -1 none
  int regions = 0;

  // Gives the pyramid's buffers back to the pool (pyramid/bip.h) once the frame is done with
  // it; the region labels are kept, to be refilled by the next frame.
  void Release() {
    builder.Release();
    bip = nullptr;
  }
  // Region of every vertex, from the top level down.
  void LabelRegions();
  // The cell of level l at absolute cell (x, y), or -1 outside the crop.
  int Cell(int l, int x, int y) const {
    const BipLevel& level = bip->level(l);
    const int cx = x - (origin.x >> l), cy = y - (origin.y >> l);
    if (cx < 0 || cy < 0 || cx >= level.cols || cy >= level.rows) return -1;
    return cy * level.cols + cx;
  }
};

// The cells of level l whose pixels lie inside `box` (level-0 pixels), in absolute cells.
cv::Rect CellsInside(const cv::Rect& box, int l);

// `bounds` grown to the top left to the nearest multiple of kAlignment, so that cells keep their
// absolute positions from frame to frame.
cv::Rect Aligned(const cv::Rect& bounds);

// Builds `hierarchy` over the pixels of `mask` (frame size) in `bounds` (aligned), with the
// similarity's features and the threshold schedule of an image whose smaller side is
// `schedule_side` (0: the crop's). `cylinder`: the frame's cylinder image when the caller has
// it (the same values as converting the crop).
void BuildHierarchy(const cv::Mat& frame, const cv::Mat& skin, TrackSimilarity similarity,
                    const cv::Mat& mask, cv::Rect bounds, int schedule_side, float t_max,
                    Hierarchy* hierarchy, const cv::Mat& cylinder = cv::Mat());

// The pyramids of a frame, colour and skin, one per group of ROIs; each keeps its buffers from
// frame to frame.
class RoiPyramids {
 public:
  // `pool`: where the pyramids borrow their levels (pyramid/bip.h); it must outlive them.
  explicit RoiPyramids(BipPool* pool) : pool_(pool) {}

  // Builds the pyramid over the union of `rois` (per target, empty for a target of another
  // similarity or outside the image) in parts, or whole when `in_parts` is false (the same
  // results; TrackerOptions::pyramid_parts). Returns the tallest part's number of levels, 0
  // when every ROI is empty. Adds the time spent to `*segmentation_ms`.
  int Build(const cv::Mat& frame, const cv::Mat& skin, const cv::Mat& cylinder,
            TrackSimilarity similarity, const std::vector<cv::Rect>& rois, float t_max,
            bool in_parts, double* segmentation_ms);
  // The part of the last Build that holds target `target`'s ROI; nullptr for an empty ROI.
  const Hierarchy* PartOf(TrackSimilarity similarity, size_t target) const;
  // The `index`-th pyramid of a similarity, made on first use.
  Hierarchy& Pyramid(TrackSimilarity similarity, size_t index);
  // Gives every pyramid's levels back to the pool, at the end of a frame's tracking.
  void Release();

 private:
  // Joins group b into group a (a < b): their crops and spans, and the targets' group numbers.
  void Merge(size_t a, size_t b, std::vector<cv::Rect>* groups, std::vector<cv::Rect>* spans);

  BipPool* pool_;
  std::vector<std::unique_ptr<Hierarchy>> pools_[2];  // colour, skin
  std::vector<int> group_of_;  // per target: its part in the last Build, -1 for an empty ROI
  cv::Mat union_mask_;
};

}  // namespace tracker_internal
}  // namespace attend
