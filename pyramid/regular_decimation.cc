// Stage 1 of building a level (pyramid/bip.h): the squared distances between neighbouring
// cells, then regular decimation.
#include <algorithm>
#include <bit>
#include <cstdint>

#include "pyramid/bip.h"
#include "pyramid/bip_internal.h"
#include "util/vector_clones.h"

namespace attend {

namespace {

// The loops over whole planes below are compiled for AVX2 and for SSE2, with the same results
// (util/vector_clones.h).

// Interleaved 3-float features to one plane per component.
ATTEND_VECTOR_CLONES void SplitPlanes(const float* __restrict feature, size_t count,
                                      float* __restrict p0, float* __restrict p1,
                                      float* __restrict p2) {
  for (size_t i = 0; i < count; ++i) {
    p0[i] = feature[3 * i];
    p1[i] = feature[3 * i + 1];
    p2[i] = feature[3 * i + 2];
  }
}

// d[i] = |f(i) - f(i + offset)|^2 for i in [begin, end), f given as three planes.
ATTEND_VECTOR_CLONES void PlaneDistances(const float* p0, const float* p1, const float* p2,
                                         size_t begin, size_t end, size_t offset,
                                         float* __restrict d) {
  for (size_t i = begin; i < end; ++i) {
    const float a = p0[i] - p0[i + offset], b = p1[i] - p1[i + offset], c = p2[i] - p2[i + offset];
    d[i] = a * a + b * b + c * c;
  }
}

// d[i] = the hole marker for i in [begin, end) where cell i or i + offset is a hole.
ATTEND_VECTOR_CLONES void MarkHoles(const uint8_t* hom, size_t begin, size_t end, size_t offset,
                                    float* __restrict d) {
  const float hole = std::bit_cast<float>(kHoleBits);
  for (size_t i = begin; i < end; ++i) d[i] = (hom[i] & hom[i + offset]) != 0 ? d[i] : hole;
}

}  // namespace

void BipBuilder::NeighbourDistances(int l) {
  const BipLevel& cur = (*levels_)[l];
  const int cols = cur.cols, rows = cur.rows;
  const size_t cells = static_cast<size_t>(cols) * rows;
  // Grow only: resizing back up after a smaller level would zero-fill every frame.
  for (auto& plane : scratch_->distance_) {
    if (plane.size() < cells) Fit(&plane, cells);
  }
  if (cells == 0) return;  // a 1-wide level halves to 0 columns
  // One plane per feature component, so that the loops below vectorise.
  for (auto& plane : scratch_->planes_) {
    if (plane.size() < cells) Fit(&plane, cells);
  }
  const float* p0 = scratch_->planes_[0].data();
  const float* p1 = scratch_->planes_[1].data();
  const float* p2 = scratch_->planes_[2].data();
  SplitPlanes(cur.feature.data(), cells, scratch_->planes_[0].data(), scratch_->planes_[1].data(),
              scratch_->planes_[2].data());
  // With holes, a pair with a hole gets kHoleBits, so that stage 2 need not look at Hom.
  const bool holes = cur.num_regular < static_cast<int>(cells);
  auto distances = [&](float* d, size_t begin, size_t end, size_t offset) {
    PlaneDistances(p0, p1, p2, begin, end, offset, d);
    if (holes) MarkHoles(cur.hom.data(), begin, end, offset, d);
  };
  float* east = scratch_->distance_[kEast].data();
  float* south = scratch_->distance_[kSouth].data();
  float* south_east = scratch_->distance_[kSouthEast].data();
  float* south_west = scratch_->distance_[kSouthWest].data();
  // Whole-plane passes; the entries that wrap around a row end are overwritten below.
  distances(east, 0, cells - 1, 1);
  east[cells - 1] = kFar;
  const size_t last_row = cells - cols;
  distances(south, 0, last_row, cols);
  if (last_row > 0) {
    distances(south_east, 0, last_row - 1, cols + 1);
    distances(south_west, 1, last_row, cols - 1);
  }
  std::fill(south + last_row, south + cells, kFar);
  std::fill(south_east + (last_row > 0 ? last_row - 1 : 0), south_east + cells, kFar);
  std::fill(south_west + last_row, south_west + cells, kFar);
  for (int row = 0; row < rows; ++row) {
    const size_t first = static_cast<size_t>(row) * cols;
    east[first + cols - 1] = kFar;
    south_east[first + cols - 1] = kFar;
    south_west[first] = kFar;
  }
}

// Stage 1: (i, j, l+1) is a regular vertex iff its four sons are regular and pairwise similar.
// Its area and (not yet divided) feature sum are set here. Every cell of l + 1 is written, and
// every window's sons get their parent or -1 (which they hold already), without a branch:
// which windows pass is unpredictable in textured areas.
void BipBuilder::RegularDecimation(int l, float t2) {
  const BipLevel& cur = (*levels_)[l];
  BipLevel& up = (*levels_)[l + 1];
  const float* east = scratch_->distance_[kEast].data();
  const float* south = scratch_->distance_[kSouth].data();
  const float* south_east = scratch_->distance_[kSouthEast].data();
  const float* south_west = scratch_->distance_[kSouthWest].data();
  // Plain pointers and a local count: the Hom bytes written below may alias anything, which
  // would make the compiler reload every vector's data and the count after each window.
  const float* son_feature = cur.feature.data();
  const int32_t* son_area = cur.area.data();
  int32_t* son_parent = (*levels_)[l].parent.data();
  uint8_t* hom = up.hom.data();
  int32_t* area = up.area.data();
  float* feature = up.feature.data();
  const int cols = cur.cols;
  int regulars = 0;
  for (int row = 0; row < up.rows; ++row) {
    for (int col = 0; col < up.cols; ++col) {
      const int a = 2 * row * cols + 2 * col;
      const int b = a + 1, c = a + cols, d = c + 1;
      // The six pairs of the 2x2 window are similar; this fails when a son is a hole, as its
      // distances are the hole marker.
      const bool regular = (east[a] < t2) & (east[c] < t2) & (south[a] < t2) & (south[b] < t2) &
                           (south_east[a] < t2) & (south_west[b] < t2);
      const int id = row * up.cols + col;
      float sum[3] = {0.f, 0.f, 0.f};
      int sum_area = 0;
      for (int son : {a, b, c, d}) {
        son_parent[son] = regular ? id : -1;
        const float weight = static_cast<float>(son_area[son]);
        const float* f = son_feature + 3 * static_cast<size_t>(son);
        sum[0] += weight * f[0];
        sum[1] += weight * f[1];
        sum[2] += weight * f[2];
        sum_area += son_area[son];
      }
      hom[id] = regular;
      regulars += regular;
      area[id] = regular ? sum_area : 0;
      for (int k = 0; k < 3; ++k) feature[3 * static_cast<size_t>(id) + k] = regular ? sum[k] : 0.f;
    }
  }
  up.num_regular = regulars;
}

}  // namespace attend
