// Stages 2 and 3 of building a level (pyramid/bip.h): the orphans that regular decimation
// left, regular ones in raster order then virtual ones, each taking a neighbour's parent
// (parent search) or sharing a new virtual parent with an orphan neighbour (twining, virtual
// linking).
#include <algorithm>
#include <bit>
#include <cstdint>

#include "pyramid/bip.h"
#include "pyramid/bip_internal.h"

namespace attend {

namespace {

inline float Distance2(const float* a, const float* b) {
  const float d0 = a[0] - b[0], d1 = a[1] - b[1], d2 = a[2] - b[2];
  return d0 * d0 + d1 * d1 + d2 * d2;
}

// Keeps the most similar candidate seen so far (the first of equals). Written without a
// branch: which neighbour is closest is unpredictable in textured areas.
struct Best {
  int id = -1;
  float distance2 = kFar;
  void Offer(int candidate, float d2) {
    const bool closer = d2 < distance2;
    distance2 = closer ? d2 : distance2;
    id = closer ? candidate : id;
  }
};

// A neighbour of the 8-neighbourhood as one integer: its squared distance above its position
// (0..7, raster order). The bits of non-negative floats order like their values, so the
// smallest key is the most similar neighbour and, among equals, the first in raster order;
// comparing integers lets the choice run without branches and with short dependency chains.
// Keys from kNoNeighbour up (a hole's, or none) stand for no neighbour.
constexpr uint64_t kNoNeighbour = uint64_t{kHoleBits} << 3;
inline uint64_t NeighbourKey(float d2, int position) {
  return (uint64_t{std::bit_cast<uint32_t>(d2)} << 3) | static_cast<uint64_t>(position);
}

// The squared distances between neighbouring cells of the current level
// (BipScratch::distance_), by direction.
struct CellDistances {
  const float* east;
  const float* south;
  const float* south_east;
  const float* south_west;
};

// An orphan's candidates: its most similar neighbour that has a parent, and its most similar
// orphan neighbour.
struct Candidates {
  Best parented, orphan;
};

// The candidates of a cell off the border among its eight neighbours (at offsets `grid`, in
// raster order), chosen without a branch: whether there is one is unpredictable.
inline Candidates InteriorCandidates(const BipLevel& cur, const CellDistances& distances,
                                     const int* grid, int id) {
  const int cols = cur.cols;
  // The squared distances to the neighbours, in the order of `grid`.
  float d2[8];
  d2[0] = distances.south_east[id - cols - 1];
  d2[1] = distances.south[id - cols];
  d2[2] = distances.south_west[id - cols + 1];
  d2[3] = distances.east[id - 1];
  d2[4] = distances.east[id];
  d2[5] = distances.south_west[id];
  d2[6] = distances.south[id];
  d2[7] = distances.south_east[id];
  uint64_t parented_key = kNoNeighbour, orphan_key = kNoNeighbour;
  for (int k = 0; k < 8; ++k) {
    // A hole's distance is kHoleBits: its key is no neighbour.
    const uint64_t key = NeighbourKey(d2[k], k);
    const bool has_parent = cur.parent[id + grid[k]] >= 0;
    parented_key = std::min(parented_key, has_parent ? key : kNoNeighbour);
    orphan_key = std::min(orphan_key, has_parent ? kNoNeighbour : key);
  }
  // The most similar neighbour among those of one kind, from its key.
  auto best_of = [&](uint64_t key) {
    const bool found = key < kNoNeighbour;
    Best best;
    best.id = found ? id + grid[key & 7] : -1;
    best.distance2 = found ? std::bit_cast<float>(static_cast<uint32_t>(key >> 3)) : kFar;
    return best;
  };
  return {best_of(parented_key), best_of(orphan_key)};
}

// The candidates of a cell on the border, offered in raster order of the neighbours so that
// ties go to the first.
inline Candidates BorderCandidates(const BipLevel& cur, const CellDistances& distances, int row,
                                   int col) {
  const int cols = cur.cols, id = row * cols + col;
  const float* east = distances.east;
  const float* south = distances.south;
  const float* south_east = distances.south_east;
  const float* south_west = distances.south_west;
  Candidates found;
  auto offer = [&](int n, float d2) {
    if (cur.hom[n] == 0) return;
    if (cur.parent[n] >= 0) {
      found.parented.Offer(n, d2);
    } else {
      found.orphan.Offer(n, d2);
    }
  };
  if (row > 0 && col > 0) offer(id - cols - 1, south_east[id - cols - 1]);
  if (row > 0) offer(id - cols, south[id - cols]);
  if (row > 0 && col + 1 < cols) offer(id - cols + 1, south_west[id - cols + 1]);
  if (col > 0) offer(id - 1, east[id - 1]);
  if (col + 1 < cols) offer(id + 1, east[id]);
  if (row + 1 < cur.rows && col > 0) offer(id + cols - 1, south_west[id]);
  if (row + 1 < cur.rows) offer(id + cols, south[id]);
  if (row + 1 < cur.rows && col + 1 < cols) offer(id + cols + 1, south_east[id]);
  return found;
}

}  // namespace

void BipBuilder::BuildAdjacency(int l) {
  const BipLevel& cur = (*levels_)[l];
  if (cur.edges.empty()) {  // level 0, and levels without virtual vertices
    scratch_->adjacency_offsets_.clear();
    scratch_->adjacency_.clear();
    return;
  }
  const int ids = cur.num_ids();
  scratch_->adjacency_offsets_.assign(ids + 1, 0);
  for (uint64_t key : cur.edges) {
    ++scratch_->adjacency_offsets_[(key >> 32) + 1];
    ++scratch_->adjacency_offsets_[(key & 0xffffffffu) + 1];
  }
  for (int i = 0; i < ids; ++i)
    scratch_->adjacency_offsets_[i + 1] += scratch_->adjacency_offsets_[i];
  scratch_->adjacency_.resize(2 * cur.edges.size());
  scratch_->stamp_.assign(scratch_->adjacency_offsets_.begin(),
                          scratch_->adjacency_offsets_.end() - 1);  // fill cursor
  for (uint64_t key : cur.edges) {
    const auto a = static_cast<int32_t>(key >> 32), b = static_cast<int32_t>(key & 0xffffffffu);
    scratch_->adjacency_[scratch_->stamp_[a]++] = b;
    scratch_->adjacency_[scratch_->stamp_[b]++] = a;
  }
}

int BipBuilder::NewVirtual(BipLevel* up) {
  // Its feature, area and parent are added once the stages that make them are done.
  const int id = up->num_cells() + up->num_virtual;
  ++up->num_virtual;
  return id;
}

// The decision shared by stages 2 and 3: the parent of the most similar neighbour that has
// one (conditions 1 and 3), else a new virtual parent shared with the most similar orphan
// neighbour (conditions 2 and 3), each only below the threshold.
void BipBuilder::Link(int l, int id, int parented, float parented_d2, int orphan, float orphan_d2,
                      float t2) {
  BipLevel& cur = (*levels_)[l];
  if (parented_d2 < t2) {
    cur.parent[id] = cur.parent[parented];
    scratch_->linked_.push_back(id);
  } else if (orphan_d2 < t2) {
    const int fresh = NewVirtual(&(*levels_)[l + 1]);
    cur.parent[id] = fresh;
    cur.parent[orphan] = fresh;
    scratch_->linked_.push_back(id);
    scratch_->linked_.push_back(orphan);
  }
}

// Stage 2, in raster order: parent search (condition 1), else intra-level twining
// (condition 2). Each orphan of the scan reads what the earlier ones linked.
void BipBuilder::RegularOrphans(int l, float t2) {
  BipLevel& cur = (*levels_)[l];
  const bool across = options_.link_across_kinds;
  const CellDistances distances = {
      scratch_->distance_[kEast].data(), scratch_->distance_[kSouth].data(),
      scratch_->distance_[kSouthEast].data(), scratch_->distance_[kSouthWest].data()};
  const int cols = cur.cols;
  const int grid[8] = {-cols - 1, -cols, -cols + 1, -1, 1, cols - 1, cols, cols + 1};
  scratch_->row_orphans_.resize(cols);
  for (int row = 0; row < cur.rows; ++row) {
    // The row's orphans, gathered without a branch per cell: whether a cell is an orphan
    // alternates unpredictably in textured areas.
    const int first = row * cols;
    int count = 0;
    for (int col = 0; col < cols; ++col) {
      scratch_->row_orphans_[count] = col;
      count += (cur.hom[first + col] != 0) & (cur.parent[first + col] < 0);
    }
    for (int k = 0; k < count; ++k) {
      const int col = scratch_->row_orphans_[k];
      const int id = first + col;
      if (cur.parent[id] >= 0) continue;  // twinned earlier in this row
      Candidates found = row > 0 && col > 0 && row + 1 < cur.rows && col + 1 < cols
                             ? InteriorCandidates(cur, distances, grid, id)
                             : BorderCandidates(cur, distances, row, col);
      if (across) {
        const float* colour = cur.Feature(id);
        for (int e = AdjacencyBegin(id); e < AdjacencyEnd(id); ++e) {
          const int n = scratch_->adjacency_[e];
          const float d2 = Distance2(colour, cur.Feature(n));
          if (cur.parent[n] >= 0) {
            found.parented.Offer(n, d2);
          } else {
            found.orphan.Offer(n, d2);
          }
        }
      }
      Link(l, id, found.parented.id, found.parented.distance2, found.orphan.id,
           found.orphan.distance2, t2);
    }
  }
}

// Stage 3, in order of creation: virtual parent search, else virtual linking (condition 3).
void BipBuilder::VirtualOrphans(int l, float t2) {
  BipLevel& cur = (*levels_)[l];
  const bool across = options_.link_across_kinds;
  for (int id = cur.num_cells(); id < cur.num_ids(); ++id) {
    if (cur.parent[id] >= 0) continue;
    const float* colour = cur.Feature(id);
    Best parented, orphan;
    for (int e = AdjacencyBegin(id); e < AdjacencyEnd(id); ++e) {
      const int n = scratch_->adjacency_[e];
      const bool is_virtual = cur.IsVirtual(n);
      if (!is_virtual && !across) continue;
      const float d2 = Distance2(colour, cur.Feature(n));
      if (cur.parent[n] >= 0) {
        parented.Offer(n, d2);
      } else {
        orphan.Offer(n, d2);  // a regular orphan only with link_across_kinds
      }
    }
    Link(l, id, parented.id, parented.distance2, orphan.id, orphan.distance2, t2);
  }
}

}  // namespace attend
