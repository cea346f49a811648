#include "util/range.h"

#include <cmath>
#include <sstream>

namespace attend {

namespace {

// Formats a number without trailing zeros ("0.5", "3", "1e+06").
std::string FormatNumber(double value) {
  std::ostringstream out;
  out.precision(12);
  out << value;
  return out.str();
}

// Out of line, one conversion at a time: GCC 12.2 at -O2 turned a pair of adjacent
// double -> float -> double round trips into copies (its SLP vectoriser), which a test of the
// float bounds caught (OptionRanges.EveryRangedKeyIsRefusedOutsideItsRangeByTheFileAndByCheck).
[[gnu::noinline]] double NearestFloat(double value) {
  return static_cast<double>(static_cast<float>(value));
}

}  // namespace

Range Range::RoundedToFloat() const {
  Range rounded = *this;
  rounded.min = NearestFloat(min);
  rounded.max = NearestFloat(max);
  return rounded;
}

bool Range::Contains(double value) const {
  if (std::isnan(value)) return false;
  const bool above_min = min_open ? value > min : value >= min;
  const bool below_max = max_open ? value < max : value <= max;
  return above_min && below_max;
}

std::string Range::Describe() const {
  const bool has_min = std::isfinite(min);
  const bool has_max = std::isfinite(max);
  if (has_min && has_max) {
    return std::string("must be in ") + (min_open ? "(" : "[") + FormatNumber(min) + ", " +
           FormatNumber(max) + (max_open ? ")" : "]");
  }
  if (has_min) return std::string("must be ") + (min_open ? "> " : ">= ") + FormatNumber(min);
  if (has_max) return std::string("must be ") + (max_open ? "< " : "<= ") + FormatNumber(max);
  return "must be a finite number";
}

std::string Range::DescribeBreach(double value) const {
  if (std::isnan(value)) return Describe();
  if (min_open ? !(value > min) : !(value >= min)) {
    return std::string("must be ") + (min_open ? "> " : ">= ") + FormatNumber(min);
  }
  return std::string("must be ") + (max_open ? "< " : "<= ") + FormatNumber(max);
}

}  // namespace attend
