// The disparity estimator's maximum surface (stereo/disparity.h; Sun 2002, thesis 5.1.1): the
// two-stage dynamic programming over the correlation volume for smoothness hard and penalty.
//   stage 1, every row: Y(x, d) = C(x, d) + max_{t in -1..1} Y(x - 1, d + t), with the argmax
//            kept in 2 bits a voxel (MaximumSurfaceRow);
//   stage 2: the same recursion along y over the rows' last columns, which picks for each row
//            an end disparity consistent with its neighbours (ChooseRowEnds);
//   then every row is backtracked from its end disparity (BacktrackRow).
// Not part of the API that plugins see.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace attend {

// Stage 1's back-pointers. For every column x and every group of eight disparities
// (d = 8g .. 8g + 7) two bytes hold one bit a disparity: `a` at [2g] and `b` at [2g + 1]:
//   a and b: d(x - 1) is the best disparity of column x - 1 (a jump, penalty mode);
//   a only:  d(x - 1) = d(x);   b only: d(x - 1) = d(x) - 1;   neither: d(x - 1) = d(x) + 1.
// Comparison masks of eight lanes become these bytes with one instruction each.
constexpr int kGroup = 8;
inline int BackGroups(int depth) { return (depth + kGroup - 1) / kGroup; }

// The dynamic programming of one view: stage 1's back-pointers and row ends, stage 2's codes
// and the end disparity of every row.
struct SurfaceState {
  std::vector<uint8_t> back;         // [y][x][2 * BackGroups(depth)], 2 bits a voxel
  std::vector<int16_t> jump_from;    // [y][x]: the best disparity of column x - 1 (penalty mode)
  std::vector<float> row_ends;       // [y][d]: Y(width - 1, y, d)
  std::vector<uint8_t> column_back;  // [y][d]: stage 2's codes
  std::vector<int> ends;             // per row: the end disparity chosen by stage 2

  size_t bytes() const {
    return back.capacity() + jump_from.capacity() * sizeof(int16_t) +
           row_ends.capacity() * sizeof(float) + column_back.capacity() +
           ends.capacity() * sizeof(int);
  }
};

// Stage 1 over one row of costs ([x][d]): leaves Y(width - 1, d) in `previous` and writes the
// back-pointers, 2 * BackGroups(depth) bytes a column. `previous` and `current` point one past
// a -inf pad and have one more -inf pad after depth floats. With `jump_penalty` >= 0, d may
// also jump from the best disparity of the previous column at that cost (whose index goes to
// `jump_from[x]`); otherwise |d(x) - d(x - 1)| <= 1 holds.
void MaximumSurfaceRow(const float* costs, int width, int depth, float jump_penalty,
                       float* previous, float* current, uint8_t* back, int16_t* jump_from);

// Stage 2 (along y over the rows' ends, with |delta d| <= 1) and its backtracking: fills
// state->ends. `previous` and `current` are padded as for MaximumSurfaceRow().
void ChooseRowEnds(int height, int depth, float* previous, float* current, SurfaceState* state);

// Backtracks row y of a view from its end: calls `at(x, d)` for x = width-1 down to 0. A
// template, so that the caller's work per pixel is compiled into the loop.
template <typename Visit>
void BacktrackRow(const SurfaceState& state, int y, int width, int depth, Visit at) {
  const size_t column_bytes = 2 * static_cast<size_t>(BackGroups(depth));
  int d = state.ends[y];
  for (int x = width - 1; x >= 0; --x) {
    at(x, d);
    if (x == 0) break;
    const uint8_t* masks =
        state.back.data() + (static_cast<size_t>(y) * width + x) * column_bytes + 2 * (d / kGroup);
    const int bit = d % kGroup;
    const bool a = (masks[0] >> bit) & 1, b = (masks[1] >> bit) & 1;
    if (a && b) {
      d = state.jump_from[static_cast<size_t>(y) * width + x];
    } else if (a) {
      // d(x - 1) = d(x)
    } else {
      d += b ? -1 : 1;
    }
  }
}

}  // namespace attend
