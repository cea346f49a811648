#include "stereo/semi_global.h"

#include <algorithm>
#include <cstring>
#include <limits>

#include "util/error.h"
#include "util/vector_clones.h"

namespace attend {

namespace {

// 16 costs, one AVX2 register (two SSE2 ones in the baseline clone). The helpers below that
// take or return one are inlined into the clones, so no call passes it across the ABI that
// GCC's -Wpsabi warns about.
#pragma GCC diagnostic ignored "-Wpsabi"
typedef int16_t Shorts __attribute__((vector_size(32)));
typedef uint8_t Bytes __attribute__((vector_size(16)));
static_assert(sizeof(Shorts) == SemiGlobalAggregator::kLanes * sizeof(int16_t));

constexpr int16_t kLargest = std::numeric_limits<int16_t>::max();
// The padding around a path's costs: above any L_r, and still no overflow when P1 is added.
constexpr int16_t kPad = kLargest - SemiGlobalAggregator::kMaxPenalty;

[[gnu::always_inline]] inline Shorts Load(const int16_t* p) {
  Shorts v;
  std::memcpy(&v, p, sizeof(v));
  return v;
}
[[gnu::always_inline]] inline Shorts LoadBytes(const uint8_t* p) {
  Bytes v;
  std::memcpy(&v, p, sizeof(v));
  return __builtin_convertvector(v, Shorts);
}
[[gnu::always_inline]] inline void Store(int16_t* p, Shorts v) { std::memcpy(p, &v, sizeof(v)); }
[[gnu::always_inline]] inline Shorts Min(Shorts a, Shorts b) { return a < b ? a : b; }

// The lanes of `v` in the order of the 16 indices (GCC spells it __builtin_shuffle with a
// vector of indices, clang __builtin_shufflevector with constants; the fuzz build is clang's).
#if defined(__clang__)
#define ATTEND_SHUFFLE(v, ...) __builtin_shufflevector(v, v, __VA_ARGS__)
#else
#define ATTEND_SHUFFLE(v, ...) __builtin_shuffle(v, Shorts{__VA_ARGS__})
#endif

// The least lane of `v`.
[[gnu::always_inline]] inline int16_t LeastLane(Shorts v) {
  v = Min(v, ATTEND_SHUFFLE(v, 8, 9, 10, 11, 12, 13, 14, 15, 0, 1, 2, 3, 4, 5, 6, 7));
  v = Min(v, ATTEND_SHUFFLE(v, 4, 5, 6, 7, 0, 1, 2, 3, 4, 5, 6, 7, 0, 1, 2, 3));
  v = Min(v, ATTEND_SHUFFLE(v, 2, 3, 0, 1, 2, 3, 0, 1, 2, 3, 0, 1, 2, 3, 0, 1));
  v = Min(v, ATTEND_SHUFFLE(v, 1, 0, 1, 0, 1, 0, 1, 0, 1, 0, 1, 0, 1, 0, 1, 0));
  return v[0];
}
#undef ATTEND_SHUFFLE

// One pixel of one path, over `stride` disparities (a multiple of 16) of which the first
// `depth` are candidates:
//   out[d] = cost[d] + min(prev[d], prev[d -+ 1] + p1, prev_min + p2) - prev_min,
// and sum_out[d] = sum_in[d] + out[d] (out[d] alone without sum_in); returns min_d out[d].
// out[d] is kPad from depth on, as prev[-1] is, so that no path passes through a disparity
// that is not searched.
[[gnu::always_inline]] inline int16_t PathStep(const uint8_t* __restrict cost,
                                               const int16_t* __restrict prev, int16_t prev_min,
                                               int16_t p1, int16_t p2, int16_t* __restrict out,
                                               const int16_t* sum_in, int16_t* sum_out,
                                               int stride, const Shorts& depth) {
  const Shorts jump = Shorts{} + static_cast<int16_t>(prev_min + p2);
  const Shorts step = Shorts{} + p1;
  const Shorts base = Shorts{} + prev_min;
  const Shorts pad = Shorts{} + kPad;
  Shorts least = Shorts{} + kLargest;
  Shorts index = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15};
  for (int d = 0; d < stride; d += SemiGlobalAggregator::kLanes) {
    const Shorts side = Min(Load(prev + d - 1), Load(prev + d + 1)) + step;
    const Shorts best = Min(Min(Load(prev + d), side), jump);
    const Shorts inside = index < depth;
    const Shorts value = LoadBytes(cost + d) + best - base;
    const Shorts kept = inside ? value : pad;
    const Shorts added = inside ? value : Shorts{};
    Store(out + d, kept);
    Store(sum_out + d, sum_in == nullptr ? added : Load(sum_in + d) + added);
    least = Min(least, kept);
    index += SemiGlobalAggregator::kLanes;
  }
  return LeastLane(least);
}

// Where one row of a pass reads and writes; pointers to d = 0 of pixel 0.
struct PassRow {
  const uint8_t* cost;  // the row's costs, [x][stride]
  int16_t* sum;         // the sums of the paths from above and the left, [x][stride]
  int16_t* along[2];    // the path along the row: the pixel before and this one, by x parity
  int16_t* along_min;   // their minima, [2]
  int16_t* before[3];   // the three paths from the row before: that row's L_r, [x][slot]
  int16_t* before_min[3];
  int16_t* now[3];  // and this row's
  int16_t* now_min[3];
  int16_t* total;       // one pixel's whole sum, [stride]
  const int16_t* none;  // no predecessor: zeros
  bool first_row;
  // The outputs: the row's left disparities, and the right view's best sums and their d, the
  // right pixel xr at [width - 1 - xr] (null without the right view).
  float* left;
  int16_t* right_best;
  int16_t* right_best_d;
};

// Where the pass goes: forward is down the image and left to right.
struct Geometry {
  int width, stride, depth;
  size_t slot;
  int16_t p1, p2;
  Shorts depths;  // depth in every lane
};

// The four paths of pixel x (the `step_x`-th of its row in the pass's order) that come from
// the row before and the pixel before: sum_out = sum_in (none when null) + their costs.
[[gnu::always_inline]] inline void FourPaths(const PassRow& row, const Geometry& g, bool forward,
                                             int x, int step_x, const int16_t* sum_in,
                                             int16_t* sum_out) {
  const int back = forward ? -1 : 1;
  const uint8_t* cost = row.cost + static_cast<size_t>(x) * g.stride;
  const int here = step_x & 1;
  const bool has_previous = step_x > 0;
  row.along_min[here] = PathStep(cost, has_previous ? row.along[here ^ 1] : row.none,
                                 has_previous ? row.along_min[here ^ 1] : int16_t{0}, g.p1, g.p2,
                                 row.along[here], sum_in, sum_out, g.stride, g.depths);
  for (int path = 0; path < 3; ++path) {
    const int from = x + (path - 1) * back;
    const bool has = !row.first_row && from >= 0 && from < g.width;
    row.now_min[path][x] =
        PathStep(cost, has ? row.before[path] + static_cast<size_t>(from) * g.slot : row.none,
                 has ? row.before_min[path][from] : int16_t{0}, g.p1, g.p2,
                 row.now[path] + static_cast<size_t>(x) * g.slot, sum_out, sum_out, g.stride,
                 g.depths);
  }
}

// Pixel x's disparity from its whole sum `s`, and its candidates for the right view. Pixels
// come right to left.
[[gnu::always_inline]] inline void TakeDisparity(const PassRow& row, const Geometry& g, int x,
                                                 const int16_t* s, bool subpixel) {
  // Per lane the least sum and its first d, then the least of those and its first d; lanes
  // from depth on are no candidates.
  const Shorts largest = Shorts{} + kLargest;
  const Shorts depth = Shorts{} + static_cast<int16_t>(g.depth);
  Shorts least = largest;
  Shorts first = Shorts{};
  const Shorts lanes = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15};
  for (int d = 0; d < g.stride; d += SemiGlobalAggregator::kLanes) {
    const Shorts index = lanes + static_cast<int16_t>(d);
    const Shorts v = index < depth ? Load(s + d) : largest;
    const Shorts lower = v < least;
    least = lower ? v : least;
    first = lower ? index : first;
  }
  const int16_t value = LeastLane(least);
  const int best = LeastLane(least == value ? first : largest);
  float disparity = static_cast<float>(best);
  if (subpixel && best > 0 && best < g.depth - 1) {
    const float minus = s[best - 1], centre = s[best], plus = s[best + 1];
    const float curvature = minus - 2.f * centre + plus;
    if (curvature > 0.f) disparity += std::clamp(0.5f * (minus - plus) / curvature, -0.5f, 0.5f);
  }
  row.left[x] = disparity;
  if (row.right_best == nullptr) return;
  // Right pixel xr = x - d is at [width - 1 - x + d]. x falls, so a right pixel sees its d
  // falling: ties go to the later, smaller d. Lanes past the depth (kLargest here) and past
  // the row's start (xr < 0) land in the slack after the row or lose to a real d (every right
  // pixel has d = 0 among its candidates).
  int16_t* right = row.right_best + (g.width - 1 - x);
  int16_t* right_d = row.right_best_d + (g.width - 1 - x);
  for (int d = 0; d < g.stride; d += SemiGlobalAggregator::kLanes) {
    const Shorts index = lanes + static_cast<int16_t>(d);
    const Shorts v = index < depth ? Load(s + d) : largest;
    const Shorts kept = Load(right + d);
    const Shorts better = v <= kept;
    Store(right + d, better ? v : kept);
    Store(right_d + d, better ? index : Load(right_d + d));
  }
}

// Down the image, left to right: the four paths from above and the left, their sums stored.
// Below the first row, the pixels between the first and the last column have every
// predecessor: they take a loop without FourPaths' tests (the same steps, so the same sums).
ATTEND_VECTOR_CLONES void ForwardRow(const PassRow& row, const Geometry& g) {
  const int width = g.width;
  if (row.first_row || width < 3) {
    for (int x = 0; x < width; ++x) {
      FourPaths(row, g, true, x, x, nullptr, row.sum + static_cast<size_t>(x) * g.stride);
    }
    return;
  }
  FourPaths(row, g, true, 0, 0, nullptr, row.sum);
  for (int x = 1; x < width - 1; ++x) {
    const uint8_t* cost = row.cost + static_cast<size_t>(x) * g.stride;
    int16_t* sum = row.sum + static_cast<size_t>(x) * g.stride;
    const int here = x & 1;
    row.along_min[here] = PathStep(cost, row.along[here ^ 1], row.along_min[here ^ 1], g.p1, g.p2,
                                   row.along[here], nullptr, sum, g.stride, g.depths);
    // Path 0 comes from x + 1 of the row before, path 1 from x, path 2 from x - 1.
    for (int path = 0; path < 3; ++path) {
      const int from = x + 1 - path;
      row.now_min[path][x] =
          PathStep(cost, row.before[path] + static_cast<size_t>(from) * g.slot,
                   row.before_min[path][from], g.p1, g.p2,
                   row.now[path] + static_cast<size_t>(x) * g.slot, sum, sum, g.stride, g.depths);
    }
  }
  FourPaths(row, g, true, width - 1, width - 1, nullptr,
            row.sum + static_cast<size_t>(width - 1) * g.stride);
}

// Eight paths, up the image, right to left: the other four paths, and each pixel's disparity.
ATTEND_VECTOR_CLONES void BackwardRow(const PassRow& row, const Geometry& g, bool subpixel) {
  for (int step_x = 0; step_x < g.width; ++step_x) {
    const int x = g.width - 1 - step_x;
    FourPaths(row, g, false, x, step_x, row.sum + static_cast<size_t>(x) * g.stride, row.total);
    TakeDisparity(row, g, x, row.total, subpixel);
  }
}

// Five paths, the same row right to left: the path from the right, and each pixel's disparity.
ATTEND_VECTOR_CLONES void FromTheRightRow(const PassRow& row, const Geometry& g, bool subpixel) {
  for (int step_x = 0; step_x < g.width; ++step_x) {
    const int x = g.width - 1 - step_x;
    const int here = step_x & 1;
    const bool has_previous = step_x > 0;
    row.along_min[here] = PathStep(
        row.cost + static_cast<size_t>(x) * g.stride, has_previous ? row.along[here ^ 1] : row.none,
        has_previous ? row.along_min[here ^ 1] : int16_t{0}, g.p1, g.p2, row.along[here],
        row.sum + static_cast<size_t>(x) * g.stride, row.total, g.stride, g.depths);
    TakeDisparity(row, g, x, row.total, subpixel);
  }
}

}  // namespace

void SemiGlobalAggregator::Begin(const Setup& setup, cv::Mat* left, cv::Mat* right) {
  ATTEND_CHECK(setup.width > 0 && setup.height > 0 && setup.depth > 0) << "an empty cost volume";
  ATTEND_CHECK(setup.paths == 8 || setup.paths == 5) << "8 or 5 paths";
  ATTEND_CHECK(setup.p1 >= 0 && setup.p1 <= setup.p2 && setup.p2 <= kMaxPenalty)
      << "penalties out of range";
  setup_ = setup;
  left_ = left;
  right_ = right;
  const int width = setup.width;
  stride_ = (setup.depth + kLanes - 1) / kLanes * kLanes;
  slot_ = static_cast<size_t>(stride_) + 2 * kLanes;
  const size_t rows = setup.paths == 8 ? static_cast<size_t>(setup.height) : 1;
  const size_t voxels = rows * width * stride_;
  cost_.resize(voxels);
  sum_.resize(voxels);
  if (stride_ > setup.depth) {
    for (size_t at = 0; at < voxels; at += stride_) {
      std::fill(cost_.begin() + at + setup.depth, cost_.begin() + at + stride_, uint8_t{255});
    }
  }
  // Three paths x two rows x width pixels, the path along the row x two pixels, one pixel's
  // sum and the costs of no predecessor, each padded.
  paths_.assign((6 * static_cast<size_t>(width) + 4) * slot_, kPad);
  std::fill_n(paths_.begin() + (6 * static_cast<size_t>(width) + 3) * slot_ + kLanes, stride_,
              int16_t{0});
  minima_.assign(6 * static_cast<size_t>(width) + 2, 0);
  left->create(setup.height, width, CV_32FC1);
  if (right != nullptr) {
    right->create(setup.height, width, CV_32FC1);
    right_best_.resize(static_cast<size_t>(width) + stride_);
    right_best_d_.resize(static_cast<size_t>(width) + stride_);
  }
}

uint8_t* SemiGlobalAggregator::cost_row(int y) {
  const size_t row = setup_.paths == 8 ? static_cast<size_t>(y) : 0;
  return cost_.data() + row * setup_.width * stride_;
}

namespace {

Geometry MakeGeometry(const SemiGlobalAggregator::Setup& setup, int stride, size_t slot) {
  return {setup.width, stride, setup.depth, slot, static_cast<int16_t>(setup.p1),
          static_cast<int16_t>(setup.p2), Shorts{} + static_cast<int16_t>(setup.depth)};
}

// Points `row` at row y's outputs: the left map's row and, with a right view, the right view's
// candidates, cleared.
void OutputRow(cv::Mat* left, cv::Mat* right, std::vector<int16_t>* best,
               std::vector<int16_t>* best_d, int y, PassRow* row) {
  row->left = left->ptr<float>(y);
  row->right_best = right != nullptr ? best->data() : nullptr;
  row->right_best_d = right != nullptr ? best_d->data() : nullptr;
  if (right != nullptr) {
    std::fill(best->begin(), best->end(), kLargest);
    std::fill(best_d->begin(), best_d->end(), int16_t{0});
  }
}

// The pointers of a pass's row `step_y` (y in the image): `cost` and `sum` set by the caller.
void PointPaths(int16_t* paths, int16_t* minima, int width, size_t slot, int step_y,
                PassRow* row) {
  const int parity = step_y & 1;
  const size_t rows_slots = 6 * static_cast<size_t>(width);
  for (int path = 0; path < 3; ++path) {
    auto first = [&](int p) { return (static_cast<size_t>(path) * 2 + p) * width; };
    row->before[path] = paths + first(parity ^ 1) * slot + SemiGlobalAggregator::kLanes;
    row->before_min[path] = minima + first(parity ^ 1);
    row->now[path] = paths + first(parity) * slot + SemiGlobalAggregator::kLanes;
    row->now_min[path] = minima + first(parity);
  }
  row->along[0] = paths + rows_slots * slot + SemiGlobalAggregator::kLanes;
  row->along[1] = paths + (rows_slots + 1) * slot + SemiGlobalAggregator::kLanes;
  row->along_min = minima + rows_slots;
  row->total = paths + (rows_slots + 2) * slot + SemiGlobalAggregator::kLanes;
  row->none = paths + (rows_slots + 3) * slot + SemiGlobalAggregator::kLanes;
  row->first_row = step_y == 0;
}

}  // namespace

void SemiGlobalAggregator::EndRow(int y) {
  if (setup_.paths != 5) return;
  const Geometry g = MakeGeometry(setup_, stride_, slot_);
  PassRow row;
  PointPaths(paths_.data(), minima_.data(), setup_.width, slot_, y, &row);
  row.cost = cost_.data();
  row.sum = sum_.data();
  ForwardRow(row, g);
  OutputRow(left_, right_, &right_best_, &right_best_d_, y, &row);
  FromTheRightRow(row, g, setup_.subpixel);
  TakeRightRow(y);
}

void SemiGlobalAggregator::TakeRightRow(int y) {
  if (right_ == nullptr) return;
  float* out = right_->ptr<float>(y);
  for (int xr = 0; xr < setup_.width; ++xr) out[xr] = right_best_d_[setup_.width - 1 - xr];
}

void SemiGlobalAggregator::Finish() {
  if (setup_.paths != 8) return;
  const int width = setup_.width, height = setup_.height;
  const Geometry g = MakeGeometry(setup_, stride_, slot_);
  PassRow row;
  for (int step_y = 0; step_y < height; ++step_y) {
    PointPaths(paths_.data(), minima_.data(), width, slot_, step_y, &row);
    const size_t at = static_cast<size_t>(step_y) * width * stride_;
    row.cost = cost_.data() + at;
    row.sum = sum_.data() + at;
    ForwardRow(row, g);
  }
  for (int step_y = 0; step_y < height; ++step_y) {
    const int y = height - 1 - step_y;
    PointPaths(paths_.data(), minima_.data(), width, slot_, step_y, &row);
    const size_t at = static_cast<size_t>(y) * width * stride_;
    row.cost = cost_.data() + at;
    row.sum = sum_.data() + at;
    OutputRow(left_, right_, &right_best_, &right_best_d_, y, &row);
    BackwardRow(row, g, setup_.subpixel);
    TakeRightRow(y);
  }
}

}  // namespace attend
