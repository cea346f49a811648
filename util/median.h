// The median of a list of numbers: the middle value, or the mean of the two middle values of an
// even count; NaN for an empty list. One definition for the scorers that report medians.
#pragma once

#include <algorithm>
#include <limits>
#include <vector>

namespace attend {

inline double MedianOf(std::vector<double> values) {
  if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
  const size_t middle = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + middle, values.end());
  const double upper = values[middle];
  if (values.size() % 2 == 1) return upper;
  return 0.5 * (*std::max_element(values.begin(), values.begin() + middle) + upper);
}

}  // namespace attend
