#include "stereo/disparity.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#endif
#include <limits>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "stereo/disparity_internal.h"
#include "stereo/semi_global.h"
#include "util/enum_table.h"
#include "util/error.h"
#include "util/timer.h"
#include "util/vector_clones.h"

namespace attend {

namespace {

// With `subpixel`, the volume is kept as integers of this scale for the parabola fit.
constexpr float kCostScale = 32767.f;
// A window of this standard deviation or less (grey levels) is flat: its ZNCC is 0.
constexpr float kFlatSigma = 1e-3f;

// Stage 2's back-pointer codes: the step t in d(y - 1) = d(y) + t is code - 1.
constexpr uint8_t kFromBelow = 0;  // t = -1
constexpr uint8_t kFromSame = 1;   // t = 0
constexpr uint8_t kFromAbove = 2;  // t = +1

// Mean and standard deviation over the window around every pixel (borders replicated).
void WindowStatistics(const cv::Mat& image, int window, cv::Mat* mean, cv::Mat* sigma,
                      cv::Mat* scratch) {
  const cv::Size size(window, window);
  cv::boxFilter(image, *mean, CV_32F, size, cv::Point(-1, -1), true, cv::BORDER_REPLICATE);
  cv::multiply(image, image, *scratch);
  cv::boxFilter(*scratch, *sigma, CV_32F, size, cv::Point(-1, -1), true, cv::BORDER_REPLICATE);
  for (int y = 0; y < image.rows; ++y) {
    const float* m = mean->ptr<float>(y);
    float* s = sigma->ptr<float>(y);
    for (int x = 0; x < image.cols; ++x) s[x] = std::sqrt(std::max(0.f, s[x] - m[x] * m[x]));
  }
}

// `row` of `image` reversed and extended by `depth` replicated pixels, so that the pixel
// x - d (clamped at 0) is out[width - 1 - x + d]: contiguous in d.
void ReversedRow(const float* row, int width, int depth, float* out) {
  for (int m = 0; m < width + depth; ++m) out[m] = row[std::max(0, width - 1 - m)];
}

// The loops over d below are compiled for AVX2 and for SSE2, with the same results
// (util/vector_clones.h).

// column_sums[x][d] += L_in(x) R_in(x - d) - L_out(x) R_out(x - d): the window slides down by
// one row. `reversed_*` are right rows laid out by ReversedRow(). Without a leaving row (the
// first window), `left_out` is null.
ATTEND_VECTOR_CLONES void SlideColumnSums(const float* left_in, const float* reversed_in,
                                          const float* left_out, const float* reversed_out,
                                          int width, int depth, float* column_sums) {
  for (int x = 0; x < width; ++x) {
    const float a = left_in[x];
    const float* __restrict r_in = reversed_in + (width - 1 - x);
    float* __restrict sums = column_sums + static_cast<size_t>(x) * depth;
    if (left_out == nullptr) {
      for (int d = 0; d < depth; ++d) sums[d] += a * r_in[d];
    } else {
      const float b = left_out[x];
      const float* __restrict r_out = reversed_out + (width - 1 - x);
      for (int d = 0; d < depth; ++d) sums[d] += a * r_in[d] - b * r_out[d];
    }
  }
}

// One row of ZNCC: slides the window along the row over the column sums and normalises.
// `right_mean` and `right_inverse_sigma` are laid out by ReversedRow(); `window_sum` holds
// depth floats of scratch.
ATTEND_VECTOR_CLONES void ZnccRow(const float* column_sums, const float* left_mean,
                                  const float* left_sigma, const float* right_mean,
                                  const float* right_inverse_sigma, int width, int depth, int half,
                                  float inverse_count, float* window_sum, float* costs) {
  float* __restrict sums = window_sum;
  std::fill(sums, sums + depth, 0.f);
  for (int i = -half; i <= half; ++i) {
    const float* __restrict column =
        column_sums + static_cast<size_t>(std::clamp(i, 0, width - 1)) * depth;
    for (int d = 0; d < depth; ++d) sums[d] += column[d];
  }
  for (int x = 0; x < width; ++x) {
    if (x > 0) {
      const float* __restrict in =
          column_sums + static_cast<size_t>(std::min(x + half, width - 1)) * depth;
      const float* __restrict out =
          column_sums + static_cast<size_t>(std::max(x - half - 1, 0)) * depth;
      for (int d = 0; d < depth; ++d) sums[d] += in[d] - out[d];
    }
    const float mean = left_mean[x];
    const float inverse_sigma = left_sigma[x] > kFlatSigma ? 1.f / left_sigma[x] : 0.f;
    const float* __restrict rm = right_mean + (width - 1 - x);
    const float* __restrict ri = right_inverse_sigma + (width - 1 - x);
    float* __restrict c = costs + static_cast<size_t>(x) * depth;
    for (int d = 0; d < depth; ++d) {
      const float covariance = sums[d] * inverse_count - mean * rm[d];
      c[d] = std::clamp(covariance * inverse_sigma * ri[d], -1.f, 1.f);
    }
    for (int d = x + 1; d < depth; ++d) c[d] = -1.f;
  }
}

#if defined(__x86_64__) && defined(__GNUC__)
#define ATTEND_DISPARITY_AVX2 1
// ZnccRow eight disparities at a time, with the same operations in the same order, so the same
// results; the disparities past the last multiple of eight as ZnccRow computes them.
__attribute__((target("avx2"))) void ZnccRowAvx2(const float* column_sums, const float* left_mean,
                                                 const float* left_sigma, const float* right_mean,
                                                 const float* right_inverse_sigma, int width,
                                                 int depth, int half, float inverse_count,
                                                 float* window_sum, float* costs) {
  const int full = depth / 8 * 8;
  float* sums = window_sum;
  std::fill(sums, sums + depth, 0.f);
  for (int i = -half; i <= half; ++i) {
    const float* column = column_sums + static_cast<size_t>(std::clamp(i, 0, width - 1)) * depth;
    for (int d = 0; d < depth; ++d) sums[d] += column[d];
  }
  const __m256 count = _mm256_set1_ps(inverse_count);
  const __m256 low = _mm256_set1_ps(-1.f), high = _mm256_set1_ps(1.f);
  for (int x = 0; x < width; ++x) {
    if (x > 0) {
      const float* in = column_sums + static_cast<size_t>(std::min(x + half, width - 1)) * depth;
      const float* out = column_sums + static_cast<size_t>(std::max(x - half - 1, 0)) * depth;
      int d = 0;
      for (; d < full; d += 8) {
        const __m256 change = _mm256_sub_ps(_mm256_loadu_ps(in + d), _mm256_loadu_ps(out + d));
        _mm256_storeu_ps(sums + d, _mm256_add_ps(_mm256_loadu_ps(sums + d), change));
      }
      for (; d < depth; ++d) sums[d] += in[d] - out[d];
    }
    const float mean = left_mean[x];
    const float inverse_sigma = left_sigma[x] > kFlatSigma ? 1.f / left_sigma[x] : 0.f;
    const float* rm = right_mean + (width - 1 - x);
    const float* ri = right_inverse_sigma + (width - 1 - x);
    float* c = costs + static_cast<size_t>(x) * depth;
    const __m256 means = _mm256_set1_ps(mean), inverse_sigmas = _mm256_set1_ps(inverse_sigma);
    int d = 0;
    for (; d < full; d += 8) {
      const __m256 covariance = _mm256_sub_ps(_mm256_mul_ps(_mm256_loadu_ps(sums + d), count),
                                              _mm256_mul_ps(means, _mm256_loadu_ps(rm + d)));
      const __m256 zncc =
          _mm256_mul_ps(_mm256_mul_ps(covariance, inverse_sigmas), _mm256_loadu_ps(ri + d));
      _mm256_storeu_ps(c + d, _mm256_min_ps(_mm256_max_ps(zncc, low), high));
    }
    for (; d < depth; ++d) {
      const float covariance = sums[d] * inverse_count - mean * rm[d];
      c[d] = std::clamp(covariance * inverse_sigma * ri[d], -1.f, 1.f);
    }
    for (d = x + 1; d < depth; ++d) c[d] = -1.f;
  }
}

bool HasAvx2() {
  static const bool has = __builtin_cpu_supports("avx2");
  return has;
}
#else
bool HasAvx2() { return false; }
#endif

// The kernels in use: the AVX2 ones where the processor has AVX2, unless a test asks for the
// portable ones.
bool use_portable_kernels = false;
bool UseAvx2() { return HasAvx2() && !use_portable_kernels; }

// Stage 1's back-pointers. For every column x and every group of eight disparities
// (d = 8g .. 8g + 7) two bytes hold one bit a disparity: `a` at [2g] and `b` at [2g + 1]:
//   a and b: d(x - 1) is the best disparity of column x - 1 (a jump, penalty mode);
//   a only:  d(x - 1) = d(x);   b only: d(x - 1) = d(x) - 1;   neither: d(x - 1) = d(x) + 1.
// Comparison masks of eight lanes become these bytes with one instruction each.
constexpr int kGroup = 8;
int BackGroups(int depth) { return (depth + kGroup - 1) / kGroup; }

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

// Stage 1 over one row of costs ([x][d]): leaves Y(width - 1, d) in `previous` and writes the
// back-pointers, 2 * BackGroups(depth) bytes a column. `previous` and `current` point one past
// a -inf pad and have one more -inf pad after depth floats. With `jump_penalty` >= 0, d may
// also jump from the best disparity of the previous column at that cost (whose index goes to
// `jump_from[x]`); otherwise |d(x) - d(x - 1)| <= 1 holds. `Column` is the kernel of one
// column, compiled into each caller for its instruction set.
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

void MaximumSurfaceRow(const float* costs, int width, int depth, float jump_penalty,
                       float* previous, float* current, uint8_t* back, int16_t* jump_from) {
#ifdef ATTEND_DISPARITY_AVX2
  if (UseAvx2()) {
    MaximumSurfaceRowAvx2(costs, width, depth, jump_penalty, previous, current, back, jump_from);
    return;
  }
#endif
  SurfaceRow(costs, width, depth, jump_penalty, previous, current, back, jump_from,
             [depth](const float* cx, const float* p, float jump, float* out, uint8_t* masks) {
               SurfaceColumnScalar(cx, p, jump, 0, depth, out, masks);
             });
}

// One left pixel's correlations `c` (for d = 0..count-1) offered to the right pixels x - d,
// whose best correlation and disparity so far are `best` and `best_d` at index d.
inline void OfferToRightPixels(const float* __restrict c, float* __restrict best,
                               int32_t* __restrict best_d, int count) {
  for (int d = 0; d < count; ++d) {
    const bool better = c[d] > best[d];
    best[d] = better ? c[d] : best[d];
    best_d[d] = better ? d : best_d[d];
  }
}

// The right view's disparities of one row, winner-take-all over the same correlations: the
// right pixel xr's correlation at d is the left pixel xr + d's, C(xr + d, d); the best d wins,
// the smaller on ties (as OpenCV's SGBM makes its right view for its check). It is a pass over
// the left pixels that keeps each right pixel's best so far, stored mirrored (right pixel xr at
// width - 1 - xr) so that the loop over d runs forward through memory.
ATTEND_VECTOR_CLONES void RightViewRow(const float* costs, int width, int depth, float* best,
                                       int32_t* best_d, float* out) {
  std::fill(best, best + width, -std::numeric_limits<float>::infinity());
  std::fill(best_d, best_d + width, 0);
  for (int x = 0; x < width; ++x) {
    // Right pixel x - d sits at width - 1 - x + d.
    OfferToRightPixels(costs + static_cast<size_t>(x) * depth, best + (width - 1 - x),
                       best_d + (width - 1 - x), std::min(depth, x + 1));
  }
  for (int xr = 0; xr < width; ++xr) out[xr] = static_cast<float>(best_d[width - 1 - xr]);
}

#ifdef ATTEND_DISPARITY_AVX2
// SlideColumnSums eight disparities at a time, the same operations in the same order.
__attribute__((target("avx2"))) void SlideColumnSumsAvx2(const float* left_in,
                                                         const float* reversed_in,
                                                         const float* left_out,
                                                         const float* reversed_out, int width,
                                                         int depth, float* column_sums) {
  const int full = depth / 8 * 8;
  for (int x = 0; x < width; ++x) {
    const float a = left_in[x];
    const __m256 as = _mm256_set1_ps(a);
    const float* r_in = reversed_in + (width - 1 - x);
    float* sums = column_sums + static_cast<size_t>(x) * depth;
    int d = 0;
    if (left_out == nullptr) {
      for (; d < full; d += 8) {
        const __m256 product = _mm256_mul_ps(as, _mm256_loadu_ps(r_in + d));
        _mm256_storeu_ps(sums + d, _mm256_add_ps(_mm256_loadu_ps(sums + d), product));
      }
      for (; d < depth; ++d) sums[d] += a * r_in[d];
    } else {
      const float b = left_out[x];
      const __m256 bs = _mm256_set1_ps(b);
      const float* r_out = reversed_out + (width - 1 - x);
      for (; d < full; d += 8) {
        const __m256 change = _mm256_sub_ps(_mm256_mul_ps(as, _mm256_loadu_ps(r_in + d)),
                                            _mm256_mul_ps(bs, _mm256_loadu_ps(r_out + d)));
        _mm256_storeu_ps(sums + d, _mm256_add_ps(_mm256_loadu_ps(sums + d), change));
      }
      for (; d < depth; ++d) sums[d] += a * r_in[d] - b * r_out[d];
    }
  }
}

// RightViewRow eight disparities at a time (the same comparisons, so the same result).
__attribute__((target("avx2"))) void RightViewRowAvx2(const float* costs, int width, int depth,
                                                      float* best, int32_t* best_d, float* out) {
  std::fill(best, best + width, -std::numeric_limits<float>::infinity());
  std::fill(best_d, best_d + width, 0);
  const __m256i lanes = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
  for (int x = 0; x < width; ++x) {
    const float* c = costs + static_cast<size_t>(x) * depth;
    float* b = best + (width - 1 - x);
    int32_t* bd = best_d + (width - 1 - x);
    const int count = std::min(depth, x + 1);
    const int full = count / 8 * 8;
    for (int d = 0; d < full; d += 8) {
      const __m256 offered = _mm256_loadu_ps(c + d);
      const __m256 held = _mm256_loadu_ps(b + d);
      const __m256 better = _mm256_cmp_ps(offered, held, _CMP_GT_OQ);
      _mm256_storeu_ps(b + d, _mm256_blendv_ps(held, offered, better));
      const __m256i held_d = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(bd + d));
      const __m256i offered_d = _mm256_add_epi32(lanes, _mm256_set1_epi32(d));
      _mm256_storeu_si256(reinterpret_cast<__m256i*>(bd + d),
                          _mm256_blendv_epi8(held_d, offered_d, _mm256_castps_si256(better)));
    }
    for (int d = full; d < count; ++d) {
      const bool better = c[d] > b[d];
      b[d] = better ? c[d] : b[d];
      bd[d] = better ? d : bd[d];
    }
  }
  for (int xr = 0; xr < width; ++xr) out[xr] = static_cast<float>(best_d[width - 1 - xr]);
}
#endif

// The ZNCC volume, one row at a time. Window sums of L(x) R(x - d) are kept per column for
// all d and slid down the image (add the entering row, subtract the leaving one), then slid
// along the row; every sum is of integers below 2^24 for windows up to 15, so float holds it
// exactly and the result equals box filtering the product image. Borders are replicated.
// What CostRows computes before the rows: kept by the estimator between pairs, so that a
// stream of frames of one size allocates (and faults in) its pages once.
struct CostRowsStorage {
  cv::Mat left, right, left_mean, left_sigma, right_mean, right_sigma, scratch;
  std::vector<float> reversed_right;
  std::vector<float> column_sums;
  std::vector<float> window_sum;
  std::vector<float> right_mean_row, right_inverse_sigma_row;

  size_t bytes() const {
    size_t total = (reversed_right.capacity() + column_sums.capacity() + window_sum.capacity() +
                    right_mean_row.capacity() + right_inverse_sigma_row.capacity()) *
                   sizeof(float);
    for (const cv::Mat* m :
         {&left, &right, &left_mean, &left_sigma, &right_mean, &right_sigma, &scratch}) {
      total += m->total() * m->elemSize();
    }
    return total;
  }
};

class CostRows {
 public:
  // `storage` holds the buffers (the estimator's, or a local one); it must outlive the rows.
  CostRows(const cv::Mat& left, const cv::Mat& right, int depth, int window,
           CostRowsStorage* storage)
      : width_(left.cols),
        height_(left.rows),
        depth_(depth),
        half_(window / 2),
        left_(storage->left),
        right_(storage->right),
        left_mean_(storage->left_mean),
        left_sigma_(storage->left_sigma),
        right_mean_(storage->right_mean),
        right_sigma_(storage->right_sigma),
        reversed_right_(storage->reversed_right),
        column_sums_(storage->column_sums),
        window_sum_(storage->window_sum),
        right_mean_row_(storage->right_mean_row),
        right_inverse_sigma_row_(storage->right_inverse_sigma_row) {
    left.convertTo(left_, CV_32F);
    right.convertTo(right_, CV_32F);
    WindowStatistics(left_, window, &left_mean_, &left_sigma_, &storage->scratch);
    WindowStatistics(right_, window, &right_mean_, &right_sigma_, &storage->scratch);
    inverse_count_ = 1.f / static_cast<float>(window * window);
    reversed_right_.resize(static_cast<size_t>(height_) * (width_ + depth_));
    for (int y = 0; y < height_; ++y) {
      ReversedRow(right_.ptr<float>(y), width_, depth_, ReversedRight(y));
    }
    column_sums_.assign(static_cast<size_t>(width_) * depth_, 0.f);
    window_sum_.resize(depth_);
    right_mean_row_.resize(width_ + depth_);
    right_inverse_sigma_row_.resize(width_ + depth_);
  }

  // Calls `consume(y, costs)` for y = 0, 1, ...; costs[x * depth + d] is the ZNCC of (x, y) at
  // disparity d, -1 where x - d < 0.
  template <typename Consumer>
  void ForEachRow(std::vector<float>* costs, Consumer consume) {
    costs->resize(static_cast<size_t>(width_) * depth_);
    std::fill(column_sums_.begin(), column_sums_.end(), 0.f);
    for (int j = -half_; j <= half_; ++j) SlideDown(Clamp(j, height_), -1);
    for (int y = 0; y < height_; ++y) {
      if (y > 0) SlideDown(Clamp(y + half_, height_), Clamp(y - half_ - 1, height_));
      ReversedRow(right_mean_.ptr<float>(y), width_, depth_, right_mean_row_.data());
      ReversedRow(right_sigma_.ptr<float>(y), width_, depth_, right_inverse_sigma_row_.data());
      for (float& sigma : right_inverse_sigma_row_) {
        sigma = sigma > kFlatSigma ? 1.f / sigma : 0.f;
      }
#ifdef ATTEND_DISPARITY_AVX2
      auto* zncc_row = UseAvx2() ? ZnccRowAvx2 : ZnccRow;
#else
      auto* zncc_row = ZnccRow;
#endif
      zncc_row(column_sums_.data(), left_mean_.ptr<float>(y), left_sigma_.ptr<float>(y),
               right_mean_row_.data(), right_inverse_sigma_row_.data(), width_, depth_, half_,
               inverse_count_, window_sum_.data(), costs->data());
      consume(y, static_cast<const float*>(costs->data()));
    }
  }

 private:
  static int Clamp(int i, int n) { return std::clamp(i, 0, n - 1); }
  float* ReversedRight(int y) {
    return reversed_right_.data() + static_cast<size_t>(y) * (width_ + depth_);
  }
  // Adds row `in` to the column sums and, when `out` >= 0, removes row `out`.
  void SlideDown(int in, int out) {
#ifdef ATTEND_DISPARITY_AVX2
    auto* slide = UseAvx2() ? SlideColumnSumsAvx2 : SlideColumnSums;
#else
    auto* slide = SlideColumnSums;
#endif
    slide(left_.ptr<float>(in), ReversedRight(in), out >= 0 ? left_.ptr<float>(out) : nullptr,
          out >= 0 ? ReversedRight(out) : nullptr, width_, depth_, column_sums_.data());
  }

  int width_, height_, depth_, half_;
  float inverse_count_ = 1.f;
  cv::Mat &left_, &right_, &left_mean_, &left_sigma_, &right_mean_, &right_sigma_;
  std::vector<float>& reversed_right_;
  std::vector<float>& column_sums_;
  std::vector<float>& window_sum_;
  std::vector<float>& right_mean_row_;
  std::vector<float>& right_inverse_sigma_row_;
};

}  // namespace

namespace {

constexpr EnumTable<DisparitySmoothness, 3> kSmoothness = {{{
    {DisparitySmoothness::kHard, "hard"},
    {DisparitySmoothness::kPenalty, "penalty"},
    {DisparitySmoothness::kSgm, "sgm"},
}}};

// smoothness sgm: costs 1 - ZNCC in 0..2 as integers of this scale (0..254, bytes), the
// penalties too.
constexpr float kSgmScale = 127.f;

}  // namespace

const char* DisparitySmoothnessName(DisparitySmoothness smoothness) {
  return kSmoothness.Name(smoothness);
}

const OptionFields<DisparityOptions>& DisparityOptions::Fields() {
  using O = DisparityOptions;
  static const OptionFields<DisparityOptions> fields = {
      {"max_disparity", &O::max_disparity, Range::Closed(1, kMaxDisparity),
       "D: disparities 0..D-1 are searched; below the image width"},
      {"window", &O::window, Range::Closed(1, 31), "side of the square ZNCC window, odd"},
      {"subpixel", &O::subpixel, "parabola through the correlation peak: fractions of a pixel"},
      {"left_right_check", &O::left_right_check,
       "left-right consistency check, then fill from the farther valid neighbour"},
      {"lr_tolerance", &O::lr_tolerance, Range::AtLeast(0), "the check's tolerance, px"},
      {"smoothness", EnumField<&O::smoothness, kSmoothness>(),
       "hard: the thesis's |d(x) - d(x-1)| <= 1; penalty: jumps at jump_penalty; sgm: "
       "semi-global matching along sgm_paths paths"},
      {"jump_penalty", &O::jump_penalty, Range::AtLeast(0),
       "penalty: the cost of a jump, ZNCC units"},
      {"sgm_p1", &O::sgm_p1, Range::Closed(0, 16),
       "sgm: the cost of a step of one disparity, ZNCC units"},
      {"sgm_p2", &O::sgm_p2, Range::Closed(0, 16),
       "sgm: the cost of a larger jump, ZNCC units; at least sgm_p1"},
      {"median", &O::median, Range::Closed(0, 5),
       "a median filter of this size over the map (0: none; 3 or 5)"},
      {"sgm_paths", &O::sgm_paths, Range::Closed(5, 8),
       "sgm: 8 paths (two passes, the volume kept) or 5 (one pass, as OpenCV's SGBM)"},
      {"max_width", &O::max_width, Range::Closed(0, 1 << 16),
       "wider pairs are halved until they fit, D with them; 0: full size"}};
  return fields;
}

std::string DisparityOptions::Check() const {
  const std::string error = CheckFieldRanges(*this, Fields());
  if (!error.empty()) return error;
  if (window % 2 == 0) return "window must be odd";
  if (sgm_p2 < sgm_p1) return "sgm_p2 must be at least sgm_p1";
  if (sgm_paths != 5 && sgm_paths != 8) return "sgm_paths must be 5 or 8";
  if (median != 0 && median != 3 && median != 5) return "median must be 0, 3 or 5";
  return "";
}

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

struct DisparityEstimator::Buffers {
  cv::Mat left_grey, right_grey;         // CV_8UC1
  std::vector<float> costs;              // one row of the volume: [x][d]
  std::vector<float> right_best;         // one row of the right view: best correlation so far
  std::vector<int32_t> right_best_d;     // and its disparity
  std::vector<int16_t> volume;           // [y][x][d], ZNCC * kCostScale; only for `subpixel`
  std::vector<float> previous, current;  // D + 2 floats, padded with -inf at both ends
  SurfaceState left;                     // the left view's dynamic programming
  cv::Mat right_view;                    // the right image's disparity, for the left-right check
  cv::Mat left_small, right_small;       // the pair shrunk to max_width, when wider
  cv::Mat small_map;                     // and its disparity map
  SemiGlobalAggregator semi_global;      // smoothness sgm: the volume and the paths
  CostRowsStorage cost_rows;             // the correlation's images and window statistics
};

DisparityEstimator::DisparityEstimator(DisparityOptions options)
    : options_(options), buffers_(std::make_unique<Buffers>()) {
  const std::string error = options_.Check();
  if (!error.empty()) throw ConfigError("disparity: " + error);
}

// Defined here, where Buffers is complete, as unique_ptr's deleter needs.
DisparityEstimator::~DisparityEstimator() = default;

size_t DisparityEstimator::buffer_bytes() const {
  const Buffers& b = *buffers_;
  size_t bytes = (b.costs.capacity() + b.right_best.capacity()) * sizeof(float) +
                 b.right_best_d.capacity() * sizeof(int32_t) +
                 b.volume.capacity() * sizeof(int16_t) +
                 (b.previous.capacity() + b.current.capacity()) * sizeof(float) + b.left.bytes() +
                 b.semi_global.bytes() + b.cost_rows.bytes();
  for (const cv::Mat* m :
       {&b.left_grey, &b.right_grey, &b.right_view, &b.left_small, &b.right_small, &b.small_map}) {
    bytes += m->total() * m->elemSize();
  }
  return bytes;
}

void UsePortableDisparityKernels(bool portable) { use_portable_kernels = portable; }

void ZnccSlice(const cv::Mat& left, const cv::Mat& right, int d, int window, cv::Mat* out) {
  CV_Assert(left.type() == CV_8UC1 && right.type() == CV_8UC1 && left.size() == right.size());
  CV_Assert(d >= 0 && d < left.cols);
  out->create(left.size(), CV_32FC1);
  CostRowsStorage storage;
  CostRows rows(left, right, d + 1, window, &storage);
  std::vector<float> costs;
  rows.ForEachRow(&costs, [&](int y, const float* row) {
    float* z = out->ptr<float>(y);
    for (int x = 0; x < left.cols; ++x) z[x] = row[static_cast<size_t>(x) * (d + 1) + d];
  });
}

double DirectZncc(const cv::Mat& left, const cv::Mat& right, int x, int y, int d, int window) {
  const int half = window / 2;
  auto at = [](const cv::Mat& image, int row, int col) {
    return static_cast<double>(
        image.at<uchar>(std::clamp(row, 0, image.rows - 1), std::clamp(col, 0, image.cols - 1)));
  };
  double sl = 0, sr = 0, sll = 0, srr = 0, slr = 0;
  const int n = window * window;
  for (int j = -half; j <= half; ++j) {
    for (int i = -half; i <= half; ++i) {
      const double a = at(left, y + j, x + i), b = at(right, y + j, x - d + i);
      sl += a, sr += b, sll += a * a, srr += b * b, slr += a * b;
    }
  }
  const double ml = sl / n, mr = sr / n;
  const double vl = sll / n - ml * ml, vr = srr / n - mr * mr;
  if (vl <= 1e-6 || vr <= 1e-6) return 0.0;
  return (slr / n - ml * mr) / std::sqrt(vl * vr);
}

void DisparityEstimator::Compute(const cv::Mat& left, const cv::Mat& right, cv::Mat* disparity) {
  const Stopwatch stopwatch;
  if (left.empty() || right.empty() || left.size() != right.size()) {
    throw InputError("disparity: the left image is " + std::to_string(left.cols) + "x" +
                     std::to_string(left.rows) + " and the right one " +
                     std::to_string(right.cols) + "x" + std::to_string(right.rows) +
                     "; a stereo pair needs two images of one size");
  }
  if (options_.max_disparity >= left.cols) {
    throw InputError("disparity: max_disparity " + std::to_string(options_.max_disparity) +
                     " is not below the image width " + std::to_string(left.cols));
  }
  Buffers& b = *buffers_;
  auto grey = [](const cv::Mat& image, cv::Mat* out) {
    ATTEND_CHECK(image.depth() == CV_8U) << "disparity needs 8-bit images";
    if (image.channels() == 1) {
      image.copyTo(*out);
    } else {
      cv::cvtColor(image, *out, image.channels() == 4 ? cv::COLOR_BGRA2GRAY : cv::COLOR_BGR2GRAY);
    }
  };
  grey(left, &b.left_grey);
  grey(right, &b.right_grey);
  // Wider than max_width: the pair halved (by area) until it fits, the range with it, and the
  // map scaled back (nearest neighbour, each disparity times the factor).
  int factor = 1;
  while (options_.max_width > 0 && left.cols / factor > options_.max_width &&
         left.cols / (2 * factor) >= 2) {
    factor *= 2;
  }
  const cv::Mat* left_grey = &b.left_grey;
  const cv::Mat* right_grey = &b.right_grey;
  int depth = options_.max_disparity;
  cv::Mat* map = disparity;
  if (factor > 1) {
    const cv::Size small(left.cols / factor, left.rows / factor);
    cv::resize(b.left_grey, b.left_small, small, 0, 0, cv::INTER_AREA);
    cv::resize(b.right_grey, b.right_small, small, 0, 0, cv::INTER_AREA);
    left_grey = &b.left_small;
    right_grey = &b.right_small;
    depth = std::min((depth + factor - 1) / factor, small.width - 1);
    map = &b.small_map;
  }
  Estimate(*left_grey, *right_grey, depth, map);
  if (options_.left_right_check) {
    CheckLeftRight(b.right_view, options_.lr_tolerance, map);
    FillInvalidDisparities(map);
  }
  if (options_.median > 1) cv::medianBlur(*map, *map, options_.median);
  if (factor > 1) {
    cv::resize(*map, *disparity, left.size(), 0, 0, cv::INTER_NEAREST);
    *disparity *= static_cast<double>(factor);
  }
  milliseconds_ = stopwatch.ElapsedMs();
}

namespace {

// Stage 2 (along y over the rows' ends, with |delta d| <= 1) and its backtracking: fills
// state->ends. `previous` and `current` are padded as for MaximumSurfaceRow().
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

// Backtracks row y of a view from its end: out[x] for x = width-1 down to 0, calling
// `at(x, d)` for every pixel.
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

}  // namespace

void DisparityEstimator::Estimate(const cv::Mat& left_grey, const cv::Mat& right_grey, int depth,
                                  cv::Mat* disparity) {
  Buffers& b = *buffers_;
  const int width = left_grey.cols, height = left_grey.rows;
  if (options_.smoothness == DisparitySmoothness::kSgm) {
    EstimateSemiGlobal(left_grey, right_grey, depth, disparity);
    return;
  }

  const size_t column_bytes = 2 * static_cast<size_t>(BackGroups(depth));
  const bool both = options_.left_right_check;
  const float jump_penalty =
      options_.smoothness == DisparitySmoothness::kPenalty ? options_.jump_penalty : -1.f;

  constexpr float kNone = -std::numeric_limits<float>::infinity();
  b.previous.assign(depth + 2, kNone);
  b.current.assign(depth + 2, kNone);
  float* previous = b.previous.data() + 1;  // previous[-1] and previous[depth] stay -inf
  float* current = b.current.data() + 1;
  b.left.back.resize(static_cast<size_t>(width) * height * column_bytes);
  b.left.row_ends.resize(static_cast<size_t>(height) * depth);
  b.left.jump_from.resize(jump_penalty >= 0.f ? static_cast<size_t>(width) * height : 0);
  if (options_.subpixel) b.volume.resize(static_cast<size_t>(width) * height * depth);
  if (both) {
    b.right_view.create(height, width, CV_32FC1);
    b.right_best.resize(width);
    b.right_best_d.resize(width);
  }

  // Stage 1, row by row as the volume is computed: Y(x, d) = C(x, d) + max_t Y(x - 1, d + t).
  auto stage1 = [&](const float* costs, int y, SurfaceState* state) {
    MaximumSurfaceRow(costs, width, depth, jump_penalty, previous, current,
                      state->back.data() + static_cast<size_t>(y) * width * column_bytes,
                      state->jump_from.empty()
                          ? nullptr
                          : state->jump_from.data() + static_cast<size_t>(y) * width);
    std::copy(previous, previous + depth, state->row_ends.data() + static_cast<size_t>(y) * depth);
  };
  CostRows rows(left_grey, right_grey, depth, options_.window, &b.cost_rows);
  rows.ForEachRow(&b.costs, [&](int y, const float* c) {
    if (options_.subpixel) {
      int16_t* v = b.volume.data() + static_cast<size_t>(y) * width * depth;
      for (size_t i = 0; i < static_cast<size_t>(width) * depth; ++i) {
        v[i] = static_cast<int16_t>(std::lround(c[i] * kCostScale));
      }
    }
    stage1(c, y, &b.left);
    if (both) {
#ifdef ATTEND_DISPARITY_AVX2
      auto* right_view_row = UseAvx2() ? RightViewRowAvx2 : RightViewRow;
#else
      auto* right_view_row = RightViewRow;
#endif
      right_view_row(c, width, depth, b.right_best.data(), b.right_best_d.data(),
                     b.right_view.ptr<float>(y));
    }
  });

  // Stage 2, then every row backtracked from its end disparity.
  ChooseRowEnds(height, depth, previous, current, &b.left);
  disparity->create(height, width, CV_32FC1);
  for (int y = 0; y < height; ++y) {
    float* out = disparity->ptr<float>(y);
    BacktrackRow(b.left, y, width, depth, [&](int x, int d) {
      out[x] = static_cast<float>(d);
      if (options_.subpixel && d > 0 && d < depth - 1) {
        const int16_t* c = b.volume.data() + (static_cast<size_t>(y) * width + x) * depth + d;
        const float minus = c[-1], centre = c[0], plus = c[1];
        const float curvature = minus - 2.f * centre + plus;
        if (curvature < 0.f) {
          out[x] += std::clamp(0.5f * (minus - plus) / curvature, -0.5f, 0.5f);
        }
      }
    });
  }
}

namespace {

// Costs of one row for the semi-global aggregation, [x][stride]: 1 - ZNCC (0..2) in units of
// 1 / kSgmScale, rounded.
// Where the right window would start left of the image (d > x) there is nothing to match: a
// low cost (0.25 in ZNCC units) instead of the worst lets the paths carry the disparities of
// the pixels to the right into the image's left strip. Measured on the ten Middlebury pairs
// (docs/DISPARITY.md): the worst cost there, 254, gave a mean bad1 1.9 points higher.
constexpr uint8_t kSgmOutsideCost = 32;

ATTEND_VECTOR_CLONES void SemiGlobalCosts(const float* __restrict zncc, int width, int depth,
                                          int stride, uint8_t* __restrict costs) {
  for (int x = 0; x < width; ++x) {
    const float* z = zncc + static_cast<size_t>(x) * depth;
    uint8_t* cost = costs + static_cast<size_t>(x) * stride;
    const int inside = std::min(depth, x + 1);
    for (int d = 0; d < inside; ++d) {
      cost[d] = static_cast<uint8_t>(static_cast<int>((1.f - z[d]) * kSgmScale + 0.5f));
    }
    for (int d = inside; d < depth; ++d) cost[d] = kSgmOutsideCost;
  }
}

#ifdef ATTEND_DISPARITY_AVX2
// Eight costs of SemiGlobalCosts as 32-bit integers.
__attribute__((target("avx2"))) inline __m256i EightCosts(const float* z) {
  const __m256 t = _mm256_sub_ps(_mm256_set1_ps(1.f), _mm256_loadu_ps(z));
  return _mm256_cvttps_epi32(
      _mm256_add_ps(_mm256_mul_ps(t, _mm256_set1_ps(kSgmScale)), _mm256_set1_ps(0.5f)));
}

// SemiGlobalCosts 32 or 16 disparities at a time, with the same operations in the same order
// (subtract, multiply, add, truncate), so the same bytes; the rest as SemiGlobalCosts does.
__attribute__((target("avx2"))) void SemiGlobalCostsAvx2(const float* zncc, int width,
                                                         int depth, int stride,
                                                         uint8_t* costs) {
  // packs and packus work within 128-bit lanes; this puts the 4-byte groups back in order.
  const __m256i order = _mm256_setr_epi32(0, 4, 1, 5, 2, 6, 3, 7);
  for (int x = 0; x < width; ++x) {
    const float* z = zncc + static_cast<size_t>(x) * depth;
    uint8_t* cost = costs + static_cast<size_t>(x) * stride;
    const int inside = std::min(depth, x + 1);
    int d = 0;
    for (; d + 32 <= inside; d += 32) {
      const __m256i ab = _mm256_packs_epi32(EightCosts(z + d), EightCosts(z + d + 8));
      const __m256i cd = _mm256_packs_epi32(EightCosts(z + d + 16), EightCosts(z + d + 24));
      const __m256i bytes = _mm256_permutevar8x32_epi32(_mm256_packus_epi16(ab, cd), order);
      _mm256_storeu_si256(reinterpret_cast<__m256i*>(cost + d), bytes);
    }
    for (; d + 16 <= inside; d += 16) {
      const __m256i ab = _mm256_packs_epi32(EightCosts(z + d), EightCosts(z + d + 8));
      const __m256i bytes = _mm256_permutevar8x32_epi32(_mm256_packus_epi16(ab, ab), order);
      _mm_storeu_si128(reinterpret_cast<__m128i*>(cost + d), _mm256_castsi256_si128(bytes));
    }
    for (; d < inside; ++d) {
      cost[d] = static_cast<uint8_t>(static_cast<int>((1.f - z[d]) * kSgmScale + 0.5f));
    }
    for (; d < depth; ++d) cost[d] = kSgmOutsideCost;
  }
}
#endif

}  // namespace

void DisparityEstimator::EstimateSemiGlobal(const cv::Mat& left_grey, const cv::Mat& right_grey,
                                            int depth, cv::Mat* disparity) {
  Buffers& b = *buffers_;
  const int width = left_grey.cols;
  const auto penalty = [](float zncc_units) {
    return std::min(SemiGlobalAggregator::kMaxPenalty,
                    static_cast<int>(std::lround(zncc_units * kSgmScale)));
  };
  SemiGlobalAggregator::Setup setup;
  setup.width = width;
  setup.height = left_grey.rows;
  setup.depth = depth;
  setup.paths = options_.sgm_paths;
  setup.p1 = penalty(options_.sgm_p1);
  setup.p2 = penalty(options_.sgm_p2);
  setup.subpixel = options_.subpixel;
  SemiGlobalAggregator& aggregator = b.semi_global;
  aggregator.Begin(setup, disparity, options_.left_right_check ? &b.right_view : nullptr);
  const int stride = aggregator.stride();
  CostRows rows(left_grey, right_grey, depth, options_.window, &b.cost_rows);
  rows.ForEachRow(&b.costs, [&](int y, const float* c) {
#ifdef ATTEND_DISPARITY_AVX2
    auto* costs = UseAvx2() ? SemiGlobalCostsAvx2 : SemiGlobalCosts;
#else
    auto* costs = SemiGlobalCosts;
#endif
    costs(c, width, depth, stride, aggregator.cost_row(y));
    aggregator.EndRow(y);
  });
  aggregator.Finish();
}

void CheckLeftRight(const cv::Mat& right_view, int tolerance, cv::Mat* disparity) {
  CV_Assert(right_view.type() == CV_32FC1 && disparity->type() == CV_32FC1 &&
            right_view.size() == disparity->size());
  for (int y = 0; y < disparity->rows; ++y) {
    float* d = disparity->ptr<float>(y);
    const float* dr = right_view.ptr<float>(y);
    for (int x = 0; x < disparity->cols; ++x) {
      const int xr = x - static_cast<int>(std::lround(d[x]));
      if (xr < 0 || xr >= disparity->cols || std::abs(dr[xr] - d[x]) > tolerance) d[x] = -1.f;
    }
  }
}

void FillInvalidDisparities(cv::Mat* disparity) {
  CV_Assert(disparity->type() == CV_32FC1);
  const int width = disparity->cols;
  for (int y = 0; y < disparity->rows; ++y) {
    float* d = disparity->ptr<float>(y);
    int last_valid = -1;
    for (int x = 0; x < width; ++x) {
      if (d[x] >= 0.f) {
        last_valid = x;
        continue;
      }
      int next = x + 1;
      while (next < width && d[next] < 0.f) ++next;
      const float from_left = last_valid >= 0 ? d[last_valid] : -1.f;
      const float from_right = next < width ? d[next] : -1.f;
      float fill = 0.f;
      if (from_left >= 0.f && from_right >= 0.f) {
        fill = std::min(from_left, from_right);
      } else if (from_left >= 0.f || from_right >= 0.f) {
        fill = std::max(from_left, from_right);
      }
      std::fill(d + x, d + next, fill);
      x = next - 1;
    }
  }
}

}  // namespace attend
