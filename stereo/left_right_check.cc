#include "stereo/left_right_check.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "stereo/disparity_internal.h"
#include "stereo/kernels.h"
#include "util/vector_clones.h"

namespace attend {

namespace {

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

// RightViewRow's portable kernel: a pass over the left pixels that keeps each right pixel's
// best so far, stored mirrored (right pixel xr at width - 1 - xr) so that the loop over d runs
// forward through memory.
ATTEND_VECTOR_CLONES void RightViewRowPortable(const float* costs, int width, int depth,
                                               float* best, int32_t* best_d, float* out) {
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
// RightViewRowPortable eight disparities at a time (the same comparisons, so the same result).
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

}  // namespace

void RightViewRow(const float* costs, int width, int depth, float* best, int32_t* best_d,
                  float* out) {
#ifdef ATTEND_DISPARITY_AVX2
  if (UseAvx2DisparityKernels()) {
    RightViewRowAvx2(costs, width, depth, best, best_d, out);
    return;
  }
#endif
  RightViewRowPortable(costs, width, depth, best, best_d, out);
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
