#include "util/float_checks.h"

#include "util/error.h"
#include "util/vector_clones.h"

namespace attend {

namespace {

// Counts the values of `values[0..count)` outside [low, high] (NaN included), with no early
// exit, so that the loop vectorises.
ATTEND_VECTOR_CLONES int CountOutside(const float* values, size_t count, float low, float high) {
  int outside = 0;
  for (size_t i = 0; i < count; ++i) {
    outside += !(values[i] >= low && values[i] <= high);
  }
  return outside;
}

}  // namespace

bool AllFloatsWithin(const cv::Mat& map, float low, float high) {
  if (map.empty()) return true;
  ATTEND_CHECK(map.depth() == CV_32F) << "AllFloatsWithin needs a float matrix";
  const size_t row_values = static_cast<size_t>(map.cols) * map.channels();
  for (int y = 0; y < map.rows; ++y) {
    if (CountOutside(map.ptr<float>(y), row_values, low, high) != 0) return false;
  }
  return true;
}

}  // namespace attend
