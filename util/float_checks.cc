#include "util/float_checks.h"

#include <cstring>

#include "util/error.h"
#include "util/vector_clones.h"

namespace attend {

namespace {

// Whether any value of `values[0..count)` lies outside [low, high] (NaN included): eight
// values at a time as GCC vectors (one AVX2 comparison each in the AVX2 clone, two SSE ones in
// the baseline one), the rest one by one; no early exit, so that the loop stays branch-free.
typedef float Floats8 __attribute__((vector_size(32)));
typedef int Ints8 __attribute__((vector_size(32)));

ATTEND_VECTOR_CLONES bool AnyOutside(const float* values, size_t count, float low, float high) {
  Ints8 outside = {};
  size_t i = 0;
  for (; i + 8 <= count; i += 8) {
    Floats8 v;
    std::memcpy(&v, values + i, sizeof(v));
    outside |= ~((v >= low) & (v <= high));
  }
  bool any = false;
  for (int k = 0; k < 8; ++k) any |= outside[k] != 0;
  for (; i < count; ++i) any |= !(values[i] >= low && values[i] <= high);
  return any;
}

}  // namespace

bool AllFloatsWithin(const cv::Mat& map, float low, float high) {
  if (map.empty()) return true;
  ATTEND_CHECK(map.depth() == CV_32F) << "AllFloatsWithin needs a float matrix";
  const size_t row_values = static_cast<size_t>(map.cols) * map.channels();
  for (int y = 0; y < map.rows; ++y) {
    if (AnyOutside(map.ptr<float>(y), row_values, low, high)) return false;
  }
  return true;
}

}  // namespace attend
