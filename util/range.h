// An interval that a numeric value must lie in, open or closed at each end: the range of an
// option (util/option_fields.h) and of a configuration key (config/param_block.h).
#pragma once

#include <limits>
#include <string>

namespace attend {

struct Range {
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool min_open = false;
  bool max_open = false;

  static Range Any() { return {}; }
  static Range AtLeast(double min) { return {min}; }
  static Range Above(double min) { return {min, std::numeric_limits<double>::infinity(), true}; }
  static Range Closed(double min, double max) { return {min, max}; }
  // (min, max].
  static Range AboveUpTo(double min, double max) { return {min, max, true, false}; }
  bool Contains(double value) const;
  // "must be in [0, 1]", "must be >= 0", ...
  std::string Describe() const;
  // The range with each bound rounded to the nearest float: that of a float field.
  Range RoundedToFloat() const;
  // The bound `value` breaks: "must be >= 1", "must be < 10"; Describe() when `value` is not a
  // number.
  std::string DescribeBreach(double value) const;
};

}  // namespace attend
