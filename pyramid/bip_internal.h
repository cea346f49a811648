// What the units of the pyramid's build share (pyramid/bip.h): the build's working buffers and
// the helpers of more than one stage. Regular decimation is in regular_decimation.cc, parent
// search and twining (stages 2 and 3) in irregular_decimation.cc, the edges of a new level
// (stage 4) in level_edges.cc, the pool in bip_pool.cc; bip.cc builds level after level. Not
// part of the API that plugins see.
#pragma once

#include <cstdint>
#include <limits>
#include <vector>

#include "pyramid/bip.h"

namespace attend {

// The working buffers of a build (and of labelling its roots), lent by a BipPool.
struct BipScratch {
  // CSR adjacency of the current level's explicit edges, over all ids.
  std::vector<int32_t> adjacency_offsets_;
  std::vector<int32_t> adjacency_;
  // Squared distances between each cell of the current level and its east, south, south-east
  // and south-west neighbours (BipDirection): computed once, read by decimation and by the
  // orphans.
  std::vector<float> distance_[4];
  std::vector<float> planes_[3];  // the current level's features, one plane per component
  // The sons of each virtual vertex of the level being built (CSR), and a stamp per vertex.
  std::vector<int32_t> son_offsets_;
  std::vector<int32_t> sons_;
  std::vector<int32_t> virtual_sons_;  // ungrouped
  std::vector<int32_t> stamp_;
  // Row and column of each cell of the level being built (variant edges).
  std::vector<int32_t> cell_row_;
  std::vector<int32_t> cell_col_;
  // Columns of the orphans of one row, for stage 2.
  std::vector<int32_t> row_orphans_;
  // Vertices of the current level linked to a parent by stages 2 and 3.
  std::vector<int32_t> linked_;
  // Bip::LabelRoots.
  std::vector<int32_t> label_[2];
  std::vector<Bip::VertexRef> roots_;

  // Bytes of capacity (bip_pool.cc).
  size_t Bytes() const;
};

// The neighbours whose squared distances BipScratch::distance_ holds, by index.
enum BipDirection { kEast = 0, kSouth = 1, kSouthEast = 2, kSouthWest = 3 };

// The distance of no neighbour (past the border).
constexpr float kFar = std::numeric_limits<float>::infinity();

// The squared distance stored for a pair of cells of which one is a hole (Hom = 0): the NaN
// whose bits are all ones, which no arithmetic produces. It fails every "< threshold" test.
constexpr uint32_t kHoleBits = ~uint32_t{0};

// Resizes to n, allocating exactly n when the capacity is short: a vector grown by resize()
// alone doubles, and these are the largest buffers of a frame.
template <typename T>
void Fit(std::vector<T>* v, size_t n) {
  if (v->capacity() < n) v->reserve(n);
  v->resize(n);
}

template <typename T>
size_t CapacityBytes(const std::vector<T>& v) {
  return v.capacity() * sizeof(T);
}

// Inline, as the stages ask them once a vertex.
inline int BipBuilder::AdjacencyBegin(int id) const {
  return scratch_->adjacency_.empty() ? 0 : scratch_->adjacency_offsets_[id];
}

inline int BipBuilder::AdjacencyEnd(int id) const {
  return scratch_->adjacency_.empty() ? 0 : scratch_->adjacency_offsets_[id + 1];
}

}  // namespace attend
