#include "stereo/correlation.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "stereo/disparity_internal.h"
#include "stereo/kernels.h"
#include "util/vector_clones.h"

namespace attend {

namespace {

// A window of this standard deviation or less (grey levels) is flat: its ZNCC is 0.
constexpr float kFlatSigma = 1e-3f;

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

#ifdef ATTEND_DISPARITY_AVX2
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
#endif

}  // namespace

size_t CostRowsStorage::bytes() const {
  size_t total = (reversed_right.capacity() + column_sums.capacity() + window_sum.capacity() +
                  right_mean_row.capacity() + right_inverse_sigma_row.capacity()) *
                 sizeof(float);
  for (const cv::Mat* m :
       {&left, &right, &left_mean, &left_sigma, &right_mean, &right_sigma, &scratch}) {
    total += m->total() * m->elemSize();
  }
  return total;
}

CostRows::CostRows(const cv::Mat& left, const cv::Mat& right, int depth, int window,
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

void CostRows::Start(std::vector<float>* costs) {
  costs->resize(static_cast<size_t>(width_) * depth_);
  std::fill(column_sums_.begin(), column_sums_.end(), 0.f);
  for (int j = -half_; j <= half_; ++j) SlideDown(std::clamp(j, 0, height_ - 1), -1);
}

void CostRows::Row(int y, float* costs) {
  const auto clamp = [this](int i) { return std::clamp(i, 0, height_ - 1); };
  if (y > 0) SlideDown(clamp(y + half_), clamp(y - half_ - 1));
  ReversedRow(right_mean_.ptr<float>(y), width_, depth_, right_mean_row_.data());
  ReversedRow(right_sigma_.ptr<float>(y), width_, depth_, right_inverse_sigma_row_.data());
  for (float& sigma : right_inverse_sigma_row_) {
    sigma = sigma > kFlatSigma ? 1.f / sigma : 0.f;
  }
#ifdef ATTEND_DISPARITY_AVX2
  auto* zncc_row = UseAvx2DisparityKernels() ? ZnccRowAvx2 : ZnccRow;
#else
  auto* zncc_row = ZnccRow;
#endif
  zncc_row(column_sums_.data(), left_mean_.ptr<float>(y), left_sigma_.ptr<float>(y),
           right_mean_row_.data(), right_inverse_sigma_row_.data(), width_, depth_, half_,
           inverse_count_, window_sum_.data(), costs);
}

void CostRows::SlideDown(int in, int out) {
#ifdef ATTEND_DISPARITY_AVX2
  auto* slide = UseAvx2DisparityKernels() ? SlideColumnSumsAvx2 : SlideColumnSums;
#else
  auto* slide = SlideColumnSums;
#endif
  slide(left_.ptr<float>(in), ReversedRight(in), out >= 0 ? left_.ptr<float>(out) : nullptr,
        out >= 0 ? ReversedRight(out) : nullptr, width_, depth_, column_sums_.data());
}

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

}  // namespace attend
