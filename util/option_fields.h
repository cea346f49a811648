// The fields of an options struct, written once: each field's key, member, range (numeric
// fields), choices (a choice among names) and a one-line description. The default is the
// struct's own initialiser. Everything that names, reads, writes, checks or documents an option
// comes from the table: the struct's Check() tests the ranges (CheckFieldRanges), the
// configuration binder (pipeline/options_io.cc, ReadFields below) reads and writes every field
// with the key's line in its errors, the key lists and the `--set` help list the fields
// (DescribeFields), and a choice is an enum read through its EnumTable (EnumField).
//
//   const OptionFields<MyOptions>& MyOptions::Fields() {
//     static const OptionFields<MyOptions> fields = {
//         {"rate", &MyOptions::rate, Range::AboveUpTo(0, 1), "update rate of the model"},
//         {"window", &MyOptions::window, Range::Closed(1, 31), "window side, px"},
//         {"mode", EnumField<&MyOptions::mode, kModes>(), "thesis or bounded"}};
//     return fields;
//   }
#pragma once

#include <algorithm>
#include <cstdint>
#include <string>
#include <string_view>
#include <type_traits>
#include <variant>
#include <vector>

#include "util/error.h"
#include "util/range.h"
#include "util/strings.h"

namespace attend {

// A field whose value is one of an enum's names: read and written through its EnumTable.
template <typename Options>
struct EnumMember {
  std::string (*get)(const Options&);
  bool (*set)(Options*, std::string_view);
  const std::vector<std::string>& (*names)();
  const void* (*address)(const Options&);  // the member, to compare fields by where they live
};

// A fixed number of numbers kept in members of other types (an RGB array, a width and a
// height, a 2x2 matrix): read and written as one list of `size` numbers.
template <typename Options>
struct NumbersMember {
  std::vector<double> (*get)(const Options&);
  void (*set)(Options*, const std::vector<double>&);
  int size;
};

template <typename Options>
struct OptionField {
  // 64-bit integers are counts and seeds: written as plain integers, read in [0, the range's
  // upper bound] (ParamBlock::GetCount), or as an int when the range is an int's.
  using Member = std::variant<int Options::*, std::int64_t Options::*, std::uint64_t Options::*,
                              float Options::*, double Options::*, bool Options::*,
                              std::string Options::*, std::vector<std::string> Options::*,
                              std::vector<double> Options::*, EnumMember<Options>,
                              NumbersMember<Options>>;
  // A numeric field, with its range.
  template <typename T,
            typename = std::enable_if_t<std::is_arithmetic_v<T> && !std::is_same_v<T, bool>>>
  OptionField(std::string_view name, T Options::*member, Range range, std::string_view doc)
      : name(name), member(member), range(range), doc(doc) {}
  // A bool, string or list field; `choices` (when given) are the names a string, or each
  // element of a list, may take.
  template <typename T,
            typename = std::enable_if_t<!std::is_arithmetic_v<T> || std::is_same_v<T, bool>>>
  OptionField(std::string_view name, T Options::*member, std::string_view doc,
              const std::vector<std::string>& (*choices)() = nullptr)
      : name(name), member(member), doc(doc), choices(choices) {}
  // A list of numbers, each in `range`.
  OptionField(std::string_view name, std::vector<double> Options::*member, Range range,
              std::string_view doc)
      : name(name), member(member), range(range), doc(doc) {}
  // A fixed-size list of numbers kept in other members, each in `range`.
  OptionField(std::string_view name, NumbersMember<Options> member, Range range,
              std::string_view doc)
      : name(name), member(member), range(range), doc(doc) {}
  // An enum field (EnumField below).
  OptionField(std::string_view name, EnumMember<Options> member, std::string_view doc)
      : name(name), member(member), doc(doc), choices(member.names) {}

  std::string_view name;  // the key, as the configuration and Check() spell it
  Member member;
  Range range;           // numeric fields and each number of a list
  std::string_view doc;  // one line: what the field does
  const std::vector<std::string>& (*choices)() = nullptr;
  // false for a field that code sets but a configuration does not name (a safety bound): it is
  // checked and described, but not read or written as a key.
  bool is_key = true;
};

// `field` as one that is not a configuration key.
template <typename Options>
OptionField<Options> CodeOnly(OptionField<Options> field) {
  field.is_key = false;
  return field;
}

template <typename Options>
using OptionFields = std::vector<OptionField<Options>>;

namespace internal {

template <typename T>
struct MemberOf;
template <typename C, typename T>
struct MemberOf<T C::*> {
  using Class = C;
  using Type = T;
};

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

template <typename Options, typename T>
const void* AddressOf(const Options& options, T Options::*member) {
  return &(options.*member);
}
template <typename Options>
const void* AddressOf(const Options& options, const EnumMember<Options>& member) {
  return member.address(options);
}
template <typename Options>
const void* AddressOf(const Options&, const NumbersMember<Options>&) {
  return nullptr;
}

// The shortest text of a number field's value: a float as the float it is (0.2f as 0.2, not
// 0.200000003), a 64-bit count in all its digits.
template <typename T>
std::string NumberText(T value) {
  if constexpr (std::is_integral_v<T> && sizeof(T) == 8) {
    return std::to_string(value);
  } else if constexpr (std::is_same_v<T, float>) {
    return ShortestFloat(value);
  } else {
    return ShortestNumber(static_cast<double>(value));
  }
}

// "[2, 4, 8]".
inline std::string NumbersText(const std::vector<double>& values) {
  std::vector<std::string> texts;
  for (const double value : values) texts.push_back(ShortestNumber(value));
  return "[" + Join(texts, ", ") + "]";
}

// "" when each of `values` lies in the field's range; else "NAME each must be ..., got V".
template <typename Options>
std::string CheckNumbers(const OptionField<Options>& field, const std::vector<double>& values,
                         std::string_view separator) {
  for (const double value : values) {
    if (!field.range.Contains(value)) {
      return std::string(field.name) + std::string(separator) + "each " +
             field.range.DescribeBreach(value) + ", got " + ShortestNumber(value);
    }
  }
  return "";
}

}  // namespace internal

// The enum member `Member` read and written by the names of `Table` (util/enum_table.h).
template <auto Member, const auto& Table>
auto EnumField() {
  using Options = typename internal::MemberOf<decltype(Member)>::Class;
  return EnumMember<Options>{
      [](const Options& o) { return std::string(Table.Name(o.*Member)); },
      [](Options* o, std::string_view name) { return Table.FromName(name, &(o->*Member)); },
      []() -> const std::vector<std::string>& {
        static const std::vector<std::string> names = Table.Names();
        return names;
      },
      [](const Options& o) -> const void* { return &(o.*Member); }};
}

// Calls `visit(field, member)` for each field: `member` is the pointer to member, or the
// EnumMember of an enum field.
template <typename Options, typename Visit>
void ForEachField(const OptionFields<Options>& fields, Visit&& visit) {
  for (const OptionField<Options>& field : fields) {
    std::visit([&](const auto& member) { visit(field, member); }, field.member);
  }
}

// "" when every numeric field lies in its range and every choice is one of its names;
// otherwise "NAME must be >= MIN, got VALUE" for the first that does not (`separator` between
// the name and "must").
template <typename Options>
std::string CheckFieldRanges(const Options& options, const OptionFields<Options>& fields,
                             std::string_view separator = " ") {
  std::string error;
  ForEachField(fields, [&](const OptionField<Options>& field, const auto& member) {
    if (!error.empty()) return;
    using M = std::remove_cvref_t<decltype(member)>;
    if constexpr (std::is_member_object_pointer_v<M>) {
      using T = typename internal::MemberOf<M>::Type;
      if constexpr (std::is_arithmetic_v<T> && !std::is_same_v<T, bool>) {
        const double value = static_cast<double>(options.*member);
        const Range range = internal::RangeForType<T>(field.range);
        if (!range.Contains(value)) {
          error = std::string(field.name) + std::string(separator) + range.DescribeBreach(value) +
                  ", got " +
                  (std::is_integral_v<T> ? std::to_string(options.*member) : ShortestNumber(value));
        }
      } else if constexpr (std::is_same_v<T, std::string>) {
        if (field.choices == nullptr) return;
        const std::vector<std::string>& names = field.choices();
        const std::string& value = options.*member;
        if (std::find(names.begin(), names.end(), value) == names.end()) {
          error = std::string(field.name) + std::string(separator) + "must be one of " +
                  Join(names, ", ") + ", got '" + value + "'" + DidYouMean(value, names);
        }
      } else if constexpr (std::is_same_v<T, std::vector<double>>) {
        error = internal::CheckNumbers(field, options.*member, separator);
      }
    } else if constexpr (std::is_same_v<M, NumbersMember<Options>>) {
      error = internal::CheckNumbers(field, member.get(options), separator);
    }
  });
  return error;
}

// The field stored at `address` inside `options`; nullptr when it is not one of them.
template <typename Options>
const OptionField<Options>* FindField(const Options& options, const OptionFields<Options>& fields,
                                      const void* address) {
  for (const OptionField<Options>& field : fields) {
    const void* at = std::visit(
        [&](const auto& member) { return internal::AddressOf(options, member); }, field.member);
    if (at == address) return &field;
  }
  return nullptr;
}

// The field called `name`; it must be listed.
template <typename Options>
const OptionField<Options>& FieldNamed(const OptionFields<Options>& fields, std::string_view name) {
  for (const OptionField<Options>& field : fields) {
    if (field.name == name) return field;
  }
  ATTEND_CHECK(false) << "no field " << name;
  return fields.front();
}

// Whether a configuration key called `key` is among the fields.
template <typename Options>
bool HasKey(const OptionFields<Options>& fields, std::string_view key) {
  return std::any_of(fields.begin(), fields.end(), [&](const OptionField<Options>& field) {
    return field.is_key && field.name == key;
  });
}

// The range of the field called `name`.
template <typename Options>
const Range& RangeOf(const OptionFields<Options>& fields, std::string_view name) {
  return FieldNamed(fields, name).range;
}

// Whether the two structs hold the same value in every listed field.
template <typename Options>
bool SameFields(const Options& a, const Options& b, const OptionFields<Options>& fields) {
  bool same = true;
  ForEachField(fields, [&](const OptionField<Options>&, const auto& member) {
    using M = std::remove_cvref_t<decltype(member)>;
    if constexpr (std::is_member_object_pointer_v<M>) {
      same = same && a.*member == b.*member;
    } else if constexpr (std::is_same_v<M, NumbersMember<Options>>) {
      same = same && member.get(a) == member.get(b);
    } else {
      same = same && member.get(a) == member.get(b);
    }
  });
  return same;
}

// One line a field for help texts: "  KEY  TYPE, RANGE or CHOICES, default VALUE: DOC".
struct FieldDescription {
  std::string key;
  std::string type;  // int, number, bool, text, list, numbers (a list), or the choices "a|b|c"
  std::string range;     // "" when none
  std::string fallback;  // the default, as the configuration spells it
  std::string doc;
};

template <typename Options>
std::vector<FieldDescription> DescribeFields(const OptionFields<Options>& fields,
                                             const Options& defaults = Options()) {
  std::vector<FieldDescription> lines;
  ForEachField(fields, [&](const OptionField<Options>& field, const auto& member) {
    FieldDescription line;
    line.key = std::string(field.name);
    line.doc = std::string(field.doc);
    using M = std::remove_cvref_t<decltype(member)>;
    if constexpr (std::is_member_object_pointer_v<M>) {
      using T = typename internal::MemberOf<M>::Type;
      const T& value = defaults.*member;
      if constexpr (std::is_same_v<T, bool>) {
        line.type = "bool";
        line.fallback = value ? "true" : "false";
      } else if constexpr (std::is_arithmetic_v<T>) {
        line.type = std::is_integral_v<T> ? "int" : "number";
        line.range = field.range.Describe();
        line.fallback = internal::NumberText(value);
      } else if constexpr (std::is_same_v<T, std::string>) {
        line.type = field.choices ? Join(field.choices(), "|") : "text";
        line.fallback = "\"" + value + "\"";
      } else if constexpr (std::is_same_v<T, std::vector<double>>) {
        line.type = "numbers";
        line.range = field.range.Describe();
        line.fallback = internal::NumbersText(value);
      } else {
        line.type = field.choices ? "list of " + Join(field.choices(), "|") : "list";
        line.fallback = "[" + Join(value, ", ") + "]";
      }
    } else if constexpr (std::is_same_v<M, NumbersMember<Options>>) {
      line.type = std::to_string(member.size) + " numbers";
      line.range = field.range.Describe();
      line.fallback = internal::NumbersText(member.get(defaults));
    } else {
      line.type = Join(member.names(), "|");
      line.fallback = member.get(defaults);
    }
    lines.push_back(line);
  });
  return lines;
}

// The lines of DescribeFields as text, one a field, keys prefixed with `prefix`.
std::string FormatFieldDescriptions(const std::vector<FieldDescription>& lines,
                                    const std::string& prefix = "");

}  // namespace attend
