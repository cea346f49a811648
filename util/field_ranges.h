// The numeric fields of an options struct with their ranges, written once. The struct's
// Check() tests them (CheckFieldRanges), and a binder that reads the fields from a
// configuration gives each key the range of the field it fills (FindFieldRange, RangeOf), so a
// value from a file and a value set in code meet the same bounds, and a file's error still
// names the key and its line.
//
//   const FieldRanges<MyOptions>& MyOptions::Ranges() {
//     static const FieldRanges<MyOptions> ranges = {
//         {"rate", &MyOptions::rate, Range::AboveUpTo(0, 1)},
//         {"window", &MyOptions::window, Range::Closed(1, 31)}};
//     return ranges;
//   }
#pragma once

#include <string>
#include <string_view>
#include <type_traits>
#include <variant>
#include <vector>

#include "util/error.h"
#include "util/range.h"
#include "util/strings.h"

namespace attend {

template <typename Options>
struct FieldRange {
  std::string_view name;  // the field's name, as Check() names it
  std::variant<int Options::*, float Options::*, double Options::*> member;
  Range range;
};

template <typename Options>
using FieldRanges = std::vector<FieldRange<Options>>;

namespace internal {

// A float field is compared with its range's bounds rounded to float, so that the value a
// binder accepted (a double in the range) stays in it once stored: 0.01 is not a float, and
// 0.01f < 0.01.
template <typename T>
Range RangeForType(const Range& range) {
  if constexpr (std::is_same_v<T, float>) {
    return range.RoundedToFloat();
  } else {
    return range;
  }
}

}  // namespace internal

// "" when every listed field lies in its range; otherwise "NAME must be >= MIN, got VALUE" for
// the first that does not (`separator` between the name and "must").
template <typename Options>
std::string CheckFieldRanges(const Options& options, const FieldRanges<Options>& fields,
                             std::string_view separator = " ") {
  for (const FieldRange<Options>& field : fields) {
    std::string error;
    std::visit(
        [&](auto member) {
          using T = std::remove_cvref_t<decltype(options.*member)>;
          const double value = static_cast<double>(options.*member);
          const Range range = internal::RangeForType<T>(field.range);
          if (!range.Contains(value)) {
            error = std::string(field.name) + std::string(separator) + range.DescribeBreach(value) +
                    ", got " + ShortestNumber(value);
          }
        },
        field.member);
    if (!error.empty()) return error;
  }
  return "";
}

// The range of the listed field stored at `address` inside `options`; nullptr when `address`
// is not one of them.
template <typename Options>
const Range* FindFieldRange(const Options& options, const FieldRanges<Options>& fields,
                            const void* address) {
  for (const FieldRange<Options>& field : fields) {
    const void* at =
        std::visit([&](auto member) -> const void* { return &(options.*member); }, field.member);
    if (at == address) return &field.range;
  }
  return nullptr;
}

// The range of the field called `name`; it must be listed.
template <typename Options>
const Range& RangeOf(const FieldRanges<Options>& fields, std::string_view name) {
  for (const FieldRange<Options>& field : fields) {
    if (field.name == name) return field.range;
  }
  ATTEND_CHECK(false) << "no range for field " << name;
  return fields.front().range;
}

}  // namespace attend
