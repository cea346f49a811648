// Stage 4 of building a level (pyramid/bip.h): the intra-level edges of the new level, from
// the adjacency of the sons.
#include <algorithm>
#include <cstdint>
#include <cstdlib>

#include "pyramid/bip.h"
#include "pyramid/bip_internal.h"

namespace attend {

namespace {

// The 8-neighbourhood, in raster order; ties between equally similar neighbours go to the
// first one in this order.
constexpr int kDx[8] = {-1, 0, 1, -1, 1, -1, 0, 1};
constexpr int kDy[8] = {-1, -1, -1, 0, 0, 1, 1, 1};

inline uint64_t EdgeKey(int a, int b) {
  const auto lo = static_cast<uint64_t>(std::min(a, b));
  const auto hi = static_cast<uint64_t>(std::max(a, b));
  return (lo << 32) | hi;
}

}  // namespace

// Variant only: two regular vertices of l + 1 whose reduction windows touch although their
// cells are not adjacent in the array. Parent search grows a regular parent's window past its
// 2x2 block, so this happens; the thesis leaves such pairs implicit, that is unconnected.
void BipBuilder::DistantRegularEdges(int l) {
  const BipLevel& cur = (*levels_)[l];
  BipLevel& up = (*levels_)[l + 1];
  const int first_virtual = up.num_cells();
  // Row and column of every cell of l + 1, so that the test below needs no division.
  scratch_->cell_row_.resize(first_virtual);
  scratch_->cell_col_.resize(first_virtual);
  for (int row = 0, id = 0; row < up.rows; ++row) {
    for (int col = 0; col < up.cols; ++col, ++id) {
      scratch_->cell_row_[id] = row;
      scratch_->cell_col_[id] = col;
    }
  }
  auto add = [&](int p, int q) {
    if (p < 0 || q < 0 || p == q || p >= first_virtual || q >= first_virtual) return;
    if (std::abs(scratch_->cell_row_[p] - scratch_->cell_row_[q]) <= 1 &&
        std::abs(scratch_->cell_col_[p] - scratch_->cell_col_[q]) <= 1) {
      return;  // implicit in the array
    }
    up.edges.push_back(EdgeKey(p, q));
  };
  // Sons that joined a regular parent by parent search, with their grid and explicit
  // neighbours; decimation sons of two parents are only ever array neighbours. The sons are
  // grouped by parent (counting sort) and a stamp per neighbour parent skips repeats, so each
  // pair is pushed at most once from each side.
  scratch_->son_offsets_.assign(first_virtual + 1, 0);
  for (int id : scratch_->linked_) {
    if (cur.parent[id] < first_virtual) ++scratch_->son_offsets_[cur.parent[id] + 1];
  }
  for (int p = 0; p < first_virtual; ++p)
    scratch_->son_offsets_[p + 1] += scratch_->son_offsets_[p];
  scratch_->sons_.resize(scratch_->son_offsets_[first_virtual]);
  scratch_->stamp_.assign(scratch_->son_offsets_.begin(),
                          scratch_->son_offsets_.end() - 1);  // fill cursor
  for (int id : scratch_->linked_) {
    if (cur.parent[id] < first_virtual) scratch_->sons_[scratch_->stamp_[cur.parent[id]]++] = id;
  }
  scratch_->stamp_.assign(first_virtual, -1);
  const int cols = cur.cols, rows = cur.rows;
  const int grid[8] = {-cols - 1, -cols, -cols + 1, -1, 1, cols - 1, cols, cols + 1};
  for (int p = 0; p < first_virtual; ++p) {
    if (scratch_->son_offsets_[p] == scratch_->son_offsets_[p + 1]) continue;
    const int p_row = scratch_->cell_row_[p], p_col = scratch_->cell_col_[p];
    // Cheapest and most selective tests first: most neighbours have no parent, a virtual one,
    // p or an array neighbour of p, none of which makes an edge here.
    auto visit = [&](int neighbour) {
      const int q = cur.parent[neighbour];
      if (static_cast<unsigned>(q) >= static_cast<unsigned>(first_virtual)) return;
      if (std::abs(scratch_->cell_row_[q] - p_row) <= 1 &&
          std::abs(scratch_->cell_col_[q] - p_col) <= 1)
        return;
      if (scratch_->stamp_[q] == p) return;
      scratch_->stamp_[q] = p;
      up.edges.push_back(EdgeKey(p, q));
    };
    for (int k = scratch_->son_offsets_[p]; k < scratch_->son_offsets_[p + 1]; ++k) {
      const int id = scratch_->sons_[k];
      if (!cur.IsVirtual(id)) {
        const int row = id / cols, col = id - row * cols;
        if (row > 0 && col > 0 && row + 1 < rows && col + 1 < cols) {
          for (int d = 0; d < 8; ++d) visit(id + grid[d]);
        } else {
          for (int d = 0; d < 8; ++d) {
            const int x = col + kDx[d], y = row + kDy[d];
            if (x >= 0 && y >= 0 && x < cols && y < rows) visit(y * cols + x);
          }
        }
      }
      for (int e = AdjacencyBegin(id); e < AdjacencyEnd(id); ++e) visit(scratch_->adjacency_[e]);
    }
  }
  // Explicit edges of level l between any two sons.
  for (uint64_t key : cur.edges) add(cur.parent[key >> 32], cur.parent[key & 0xffffffffu]);
  std::sort(up.edges.begin(), up.edges.end());
  up.edges.erase(std::unique(up.edges.begin(), up.edges.end()), up.edges.end());
}

// Stage 4: two vertices of l + 1 are neighbours iff their reduction windows are adjacent at l.
// Only pairs with a virtual end are stored; regular pairs are implicit in the array. Each
// virtual parent visits its sons' neighbours once, and a stamp per parent skips repeats, so no
// sorting is needed: a virtual-virtual pair is emitted by its smaller id, a virtual-regular
// pair by the virtual end.
void BipBuilder::IntraLevelEdges(int l) {
  const BipLevel& cur = (*levels_)[l];
  BipLevel& up = (*levels_)[l + 1];
  up.edges.clear();
  if (options_.link_across_kinds) DistantRegularEdges(l);
  if (up.num_virtual == 0) return;
  // The sons of each virtual parent, grouped (counting sort by parent). Only stages 2 and 3
  // give a vertex a virtual parent, so the linked sons are all there is to look at; those with
  // a virtual parent are gathered first, without a branch (the kind of parent is
  // unpredictable).
  const int first_virtual = up.num_cells();
  const int parents = up.num_ids();
  scratch_->virtual_sons_.resize(scratch_->linked_.size());
  int num_sons = 0;
  for (int id : scratch_->linked_) {
    scratch_->virtual_sons_[num_sons] = id;
    num_sons += cur.parent[id] >= first_virtual;
  }
  scratch_->son_offsets_.assign(up.num_virtual + 1, 0);
  for (int k = 0; k < num_sons; ++k) {
    ++scratch_->son_offsets_[cur.parent[scratch_->virtual_sons_[k]] - first_virtual + 1];
  }
  for (int v = 0; v < up.num_virtual; ++v)
    scratch_->son_offsets_[v + 1] += scratch_->son_offsets_[v];
  scratch_->sons_.resize(num_sons);
  scratch_->stamp_.assign(scratch_->son_offsets_.begin(),
                          scratch_->son_offsets_.end() - 1);  // fill cursor
  for (int k = 0; k < num_sons; ++k) {
    const int id = scratch_->virtual_sons_[k];
    scratch_->sons_[scratch_->stamp_[cur.parent[id] - first_virtual]++] = id;
  }
  // scratch_->stamp_[q + 1] == p once p has seen parent q; slot 0 stands for "no parent" (q = -1).
  scratch_->stamp_.assign(parents + 1, -1);
  const int cols = cur.cols, rows = cur.rows;
  const int grid[8] = {-cols - 1, -cols, -cols + 1, -1, 1, cols - 1, cols, cols + 1};
  for (int p = first_virtual; p < parents; ++p) {
    // Marking "no parent" and p itself as seen leaves one test per neighbour.
    scratch_->stamp_[0] = p;
    scratch_->stamp_[p + 1] = p;
    auto visit = [&](int neighbour) {
      const int q = cur.parent[neighbour];
      const bool seen = scratch_->stamp_[q + 1] == p;
      scratch_->stamp_[q + 1] = p;
      if (!seen && (q < first_virtual || q > p)) up.edges.push_back(EdgeKey(p, q));
    };
    for (int k = scratch_->son_offsets_[p - first_virtual];
         k < scratch_->son_offsets_[p - first_virtual + 1]; ++k) {
      const int son = scratch_->sons_[k];
      if (!cur.IsVirtual(son)) {
        const int row = son / cols, col = son - row * cols;
        if (row > 0 && col > 0 && row + 1 < rows && col + 1 < cols) {
          for (int d = 0; d < 8; ++d) visit(son + grid[d]);
        } else {
          for (int d = 0; d < 8; ++d) {
            const int x = col + kDx[d], y = row + kDy[d];
            if (x >= 0 && y >= 0 && x < cols && y < rows) visit(y * cols + x);
          }
        }
      }
      for (int e = AdjacencyBegin(son); e < AdjacencyEnd(son); ++e) visit(scratch_->adjacency_[e]);
    }
  }
}

}  // namespace attend
