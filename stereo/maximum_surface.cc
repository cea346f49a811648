#include "stereo/maximum_surface.h"

#include <algorithm>
#include <limits>

#include "stereo/kernels.h"

namespace attend {

namespace {

// Stage 2's back-pointer codes: the step t in d(y - 1) = d(y) + t is code - 1.
constexpr uint8_t kFromBelow = 0;  // t = -1
constexpr uint8_t kFromSame = 1;   // t = 0
constexpr uint8_t kFromAbove = 2;  // t = +1

// The step of one voxel, as every kernel computes it: ties keep the disparity, then take the
// smaller one, then a step, then the jump.
struct Step {
  float value;
  bool a, b;
};
inline Step VoxelStep(float below, float same, float above, float jump) {
  const float side = std::max(below, above);
  const float step = std::max(same, side);
  const bool same_wins = same >= side;
  const bool below_wins = below >= above;
  const bool jump_wins = jump > step;
  return {std::max(step, jump), same_wins || jump_wins, (!same_wins && below_wins) || jump_wins};
}

// The best value of `p[0..depth)` and its first position (penalty mode).
inline int BestDisparity(const float* p, int depth, float* best_value) {
  // The maximum in eight lanes (a loop the compiler vectorises, unlike a running maximum),
  // then its first position.
  float lanes[kGroup];
  std::fill(lanes, lanes + kGroup, p[0]);
  int d = 0;
  for (; d + kGroup <= depth; d += kGroup) {
    for (int k = 0; k < kGroup; ++k) lanes[k] = std::max(lanes[k], p[d + k]);
  }
  for (; d < depth; ++d) lanes[0] = std::max(lanes[0], p[d]);
  const float best = *std::max_element(lanes, lanes + kGroup);
  int from = 0;
  while (p[from] != best) ++from;
  *best_value = best;
  return from;
}

// Stage 1's step for disparities [first, depth) of one column, one voxel at a time: the
// portable kernel, and the AVX2 kernel's tail. `masks` is the column's 2 * BackGroups bytes.
inline void SurfaceColumnScalar(const float* cx, const float* p, float jump, int first, int depth,
                                float* out, uint8_t* masks) {
  for (int d = first; d < depth; ++d) {
    const Step step = VoxelStep(p[d - 1], p[d], p[d + 1], jump);
    const int group = d / kGroup, bit = d % kGroup;
    if (bit == 0) masks[2 * group] = masks[2 * group + 1] = 0;
    masks[2 * group] |= static_cast<uint8_t>(step.a << bit);
    masks[2 * group + 1] |= static_cast<uint8_t>(step.b << bit);
    out[d] = cx[d] + step.value;
  }
}

#ifdef ATTEND_DISPARITY_AVX2
// The same step eight disparities at a time: the same comparisons and one addition a voxel, so
// the same results as SurfaceColumnScalar.
__attribute__((target("avx2"), always_inline)) inline void SurfaceColumnAvx2(
    const float* cx, const float* p, float jump, int depth, float* out, uint8_t* masks) {
  const int full = depth / kGroup * kGroup;
  const __m256 jumps = _mm256_set1_ps(jump);
  const bool with_jumps = jump > -std::numeric_limits<float>::infinity();
  for (int d = 0; d < full; d += kGroup) {
    const __m256 below = _mm256_loadu_ps(p + d - 1);
    const __m256 same = _mm256_loadu_ps(p + d);
    const __m256 above = _mm256_loadu_ps(p + d + 1);
    const __m256 side = _mm256_max_ps(below, above);
    __m256 step = _mm256_max_ps(same, side);
    const __m256 same_wins = _mm256_cmp_ps(same, side, _CMP_GE_OQ);
    const __m256 below_wins = _mm256_cmp_ps(below, above, _CMP_GE_OQ);
    __m256 a = same_wins;
    __m256 b = _mm256_andnot_ps(same_wins, below_wins);
    if (with_jumps) {
      const __m256 jump_wins = _mm256_cmp_ps(jumps, step, _CMP_GT_OQ);
      step = _mm256_blendv_ps(step, jumps, jump_wins);
      a = _mm256_or_ps(a, jump_wins);
      b = _mm256_or_ps(b, jump_wins);
    }
    _mm256_storeu_ps(out + d, _mm256_add_ps(_mm256_loadu_ps(cx + d), step));
    masks[2 * (d / kGroup)] = static_cast<uint8_t>(_mm256_movemask_ps(a));
    masks[2 * (d / kGroup) + 1] = static_cast<uint8_t>(_mm256_movemask_ps(b));
  }
  SurfaceColumnScalar(cx, p, jump, full, depth, out, masks);
}

#endif

// Stage 1 over one row; `Column` is the kernel of one column, compiled into each caller for its
// instruction set (MaximumSurfaceRow() says the rest).
template <typename Column>
inline __attribute__((always_inline)) void SurfaceRow(const float* costs, int width, int depth,
                                                      float jump_penalty, float* previous,
                                                      float* current, uint8_t* back,
                                                      int16_t* jump_from, Column column) {
  std::copy(costs, costs + depth, previous);
  const bool jumps = jump_penalty >= 0.f;
  const size_t column_bytes = 2 * static_cast<size_t>(BackGroups(depth));
  for (int x = 1; x < width; ++x) {
    float jump = -std::numeric_limits<float>::infinity();
    if (jumps) {
      float best = 0.f;
      jump_from[x] = static_cast<int16_t>(BestDisparity(previous, depth, &best));
      jump = best - jump_penalty;
    }
    column(costs + static_cast<size_t>(x) * depth, previous, jump, current,
           back + x * column_bytes);
    std::swap(previous, current);
  }
  // After an odd number of swaps the result is in the caller's `current` array (which
  // `previous` now points to): copy it to the caller's `previous` array.
  if ((width - 1) % 2 == 1) std::copy(previous, previous + depth, current);
}

#ifdef ATTEND_DISPARITY_AVX2
__attribute__((target("avx2"))) void MaximumSurfaceRowAvx2(const float* costs, int width, int depth,
                                                           float jump_penalty, float* previous,
                                                           float* current, uint8_t* back,
                                                           int16_t* jump_from) {
  SurfaceRow(
      costs, width, depth, jump_penalty, previous, current, back, jump_from,
      [depth](const float* cx, const float* p, float jump, float* out, uint8_t* masks)
          __attribute__((target("avx2"))) { SurfaceColumnAvx2(cx, p, jump, depth, out, masks); });
}
#endif

}  // namespace

void MaximumSurfaceRow(const float* costs, int width, int depth, float jump_penalty,
                       float* previous, float* current, uint8_t* back, int16_t* jump_from) {
#ifdef ATTEND_DISPARITY_AVX2
  if (UseAvx2DisparityKernels()) {
    MaximumSurfaceRowAvx2(costs, width, depth, jump_penalty, previous, current, back, jump_from);
    return;
  }
#endif
  SurfaceRow(costs, width, depth, jump_penalty, previous, current, back, jump_from,
             [depth](const float* cx, const float* p, float jump, float* out, uint8_t* masks) {
               SurfaceColumnScalar(cx, p, jump, 0, depth, out, masks);
             });
}

void ChooseRowEnds(int height, int depth, float* previous, float* current, SurfaceState* state) {
  state->column_back.assign(static_cast<size_t>(height) * depth, kFromSame);
  std::copy(state->row_ends.begin(), state->row_ends.begin() + depth, previous);
  for (int y = 1; y < height; ++y) {
    const float* ends = state->row_ends.data() + static_cast<size_t>(y) * depth;
    uint8_t* back = state->column_back.data() + static_cast<size_t>(y) * depth;
    for (int d = 0; d < depth; ++d) {
      uint8_t code = kFromSame;
      float best = previous[d];
      if (previous[d - 1] > best) best = previous[d - 1], code = kFromBelow;
      if (previous[d + 1] > best) best = previous[d + 1], code = kFromAbove;
      current[d] = ends[d] + best;
      back[d] = code;
    }
    std::swap(previous, current);
  }
  state->ends.resize(height);
  int d = static_cast<int>(std::max_element(previous, previous + depth) - previous);
  for (int y = height - 1; y >= 0; --y) {
    state->ends[y] = d;
    d += static_cast<int>(state->column_back[static_cast<size_t>(y) * depth + d]) - 1;
  }
}

}  // namespace attend
