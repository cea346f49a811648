#include "stereo/disparity.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "stereo/correlation.h"
#include "stereo/disparity_internal.h"
#include "stereo/kernels.h"
#include "stereo/left_right_check.h"
#include "stereo/maximum_surface.h"
#include "stereo/semi_global.h"
#include "util/error.h"
#include "util/timer.h"
#include "util/vector_clones.h"

// The estimator's steps are in files of their own: the correlation (stereo/correlation.h), the
// maximum surface of smoothness hard and penalty (stereo/maximum_surface.h), semi-global
// matching (stereo/semi_global.h) and the left-right check (stereo/left_right_check.h); here
// they are put together, with the costs of semi-global matching.

namespace attend {

namespace {

// With `subpixel`, the volume is kept as integers of this scale for the parabola fit.
constexpr float kCostScale = 32767.f;

// smoothness sgm: costs 1 - ZNCC in 0..2 as integers of this scale (0..254, bytes), the
// penalties too.
constexpr float kSgmScale = 127.f;

// The kernels in use: the AVX2 ones where the processor has AVX2, unless a test asks for the
// portable ones.
bool use_portable_kernels = false;

#ifdef ATTEND_DISPARITY_AVX2
bool HasAvx2() {
  static const bool has = __builtin_cpu_supports("avx2");
  return has;
}
#else
bool HasAvx2() { return false; }
#endif

}  // namespace

bool UseAvx2DisparityKernels() { return HasAvx2() && !use_portable_kernels; }

void UsePortableDisparityKernels(bool portable) { use_portable_kernels = portable; }

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
  if (options_.left_right_check) CheckLeftRight(b.right_view, options_.lr_tolerance, map);
  MarkMeasured(*map, *left_grey, depth, left.size());
  if (options_.left_right_check) FillInvalidDisparities(map);
  if (options_.median > 1) cv::medianBlur(*map, *map, options_.median);
  if (factor > 1) {
    cv::resize(*map, *disparity, left.size(), 0, 0, cv::INTER_NEAREST);
    *disparity *= static_cast<double>(factor);
  }
  milliseconds_ = stopwatch.ElapsedMs();
}

void DisparityEstimator::MarkMeasured(const cv::Mat& map, const cv::Mat& left_grey, int depth,
                                      cv::Size size) {
  // The window's grey standard deviation, from box filters of the image and its square.
  cv::Mat grey, mean, mean_square;
  left_grey.convertTo(grey, CV_32F);
  const cv::Size window(options_.window, options_.window);
  cv::boxFilter(grey, mean, CV_32F, window, cv::Point(-1, -1), true, cv::BORDER_REFLECT);
  cv::boxFilter(grey.mul(grey), mean_square, CV_32F, window, cv::Point(-1, -1), true,
                cv::BORDER_REFLECT);
  cv::Mat variance = mean_square - mean.mul(mean);
  cv::Mat measured = (variance >= kMeasuredMinTexture * kMeasuredMinTexture) & (map >= 0.f);
  // The first D - 1 columns have no partner in the right view at the larger disparities: their
  // value is the best of the shifts that fit, whatever the truth.
  measured.colRange(0, std::min(depth - 1, measured.cols)).setTo(0);
  if (measured.size() != size) {
    cv::resize(measured, measured_, size, 0, 0, cv::INTER_NEAREST);
  } else {
    measured_ = measured;
  }
}

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
      RightViewRow(c, width, depth, b.right_best.data(), b.right_best_d.data(),
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
    auto* costs = UseAvx2DisparityKernels() ? SemiGlobalCostsAvx2 : SemiGlobalCosts;
#else
    auto* costs = SemiGlobalCosts;
#endif
    costs(c, width, depth, stride, aggregator.cost_row(y));
    aggregator.EndRow(y);
  });
  aggregator.Finish();
}
}  // namespace attend
