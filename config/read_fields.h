// Reads the fields of an options struct (util/option_fields.h) from a ParamBlock: each key
// with its field's range or choices, starting from the struct's current values, so an error
// names the key and its line. A nested block (`camera: {focal_px: ...}`) is a section with a
// table of its own (ReadSection), a list of blocks one struct an element (ReadList).
#pragma once

#include <algorithm>
#include <cstdint>
#include <limits>
#include <string>
#include <type_traits>
#include <vector>

#include "config/param_block.h"
#include "util/option_fields.h"
#include "util/strings.h"

namespace attend {

namespace internal {

// The largest value a 64-bit count field takes: its range's upper bound, or the type's.
template <typename T>
std::uint64_t CountMax(const Range& range) {
  const auto type_max = static_cast<std::uint64_t>(std::numeric_limits<T>::max());
  if (!(range.max < static_cast<double>(type_max))) return type_max;
  return static_cast<std::uint64_t>(range.max);
}

}  // namespace internal

// Reads every key field of `fields` into `options`; the keys are `prefix` + the field's name.
template <typename Options>
void ReadFields(const ParamBlock& block, const OptionFields<Options>& fields, Options* options,
                const std::string& prefix = "") {
  ForEachField(fields, [&](const OptionField<Options>& field, const auto& member) {
    if (!field.is_key) return;
    const std::string key = prefix + std::string(field.name);
    using M = std::remove_cvref_t<decltype(member)>;
    if constexpr (std::is_member_object_pointer_v<M>) {
      using T = typename internal::MemberOf<M>::Type;
      T& value = options->*member;
      if constexpr (std::is_same_v<T, bool>) {
        value = block.GetBool(key, value);
      } else if constexpr (std::is_same_v<T, int>) {
        value = block.GetInt(key, value, field.range);
      } else if constexpr (std::is_integral_v<T>) {
        // Within an int's range (a scene's seed) it reads as an int does, with its messages.
        if (field.range.min >= 0 && field.range.max <= std::numeric_limits<int>::max()) {
          value = block.GetInt(key, static_cast<int>(value), field.range);
        } else {
          value = static_cast<T>(block.GetCount(key, value, internal::CountMax<T>(field.range)));
        }
      } else if constexpr (std::is_arithmetic_v<T>) {
        value = static_cast<T>(block.GetDouble(key, value, field.range));
      } else if constexpr (std::is_same_v<T, std::string>) {
        value = field.choices ? block.GetChoice(key, value, field.choices())
                              : block.GetString(key, value);
      } else if constexpr (std::is_same_v<T, std::vector<double>>) {
        value = block.GetDoubles(key, value, field.range);
      } else {
        value = block.GetStrings(key, value);
        if (field.choices == nullptr) return;
        const std::vector<std::string>& names = field.choices();
        for (const std::string& element : value) {
          if (std::find(names.begin(), names.end(), element) == names.end()) {
            block.Fail(key, "'" + element + "' is not one of " + Join(names, ", ") +
                                DidYouMean(element, names));
          }
        }
      }
    } else if constexpr (std::is_same_v<M, NumbersMember<Options>>) {
      if (block.Has(key)) {
        member.set(options, block.GetDoubles(key, {}, field.range, member.size));
      } else {
        block.GetDoubles(key, {});  // known, though absent
      }
    } else {
      const std::string name = block.GetChoice(key, member.get(*options), member.names());
      member.set(options, name);
    }
  });
}

// Reads the nested block `key` of `parent` (absent: no keys) with `fields`, then refuses the
// keys the table does not name; returns the block, for checks at its keys' lines.
template <typename Options>
ParamBlock ReadSection(const ParamBlock& parent, const std::string& key,
                       const OptionFields<Options>& fields, Options* options) {
  const ParamBlock block = parent.Child(key);
  ReadFields(block, fields, options);
  block.CheckNoUnknownKeys();
  return block;
}

// Reads each map of the list `key` of `parent` into a copy of `start` with `fields`, refusing
// keys the table does not name; `check(block, element, before)` (after the read; `before`: the
// elements read so far) may refuse an element at its keys' lines. Returns the elements.
template <typename Options, typename Check>
std::vector<Options> ReadList(const ParamBlock& parent, const std::string& key,
                              const OptionFields<Options>& fields, const Options& start,
                              const Check& check) {
  std::vector<Options> elements;
  for (const ParamBlock& block : parent.Children(key)) {
    Options element = start;
    ReadFields(block, fields, &element);
    block.CheckNoUnknownKeys();
    check(block, element, elements);
    elements.push_back(std::move(element));
  }
  return elements;
}

// The keys ReadFields reads, in order.
template <typename Options>
std::vector<std::string> FieldKeys(const OptionFields<Options>& fields,
                                   const std::string& prefix = "") {
  std::vector<std::string> keys;
  for (const OptionField<Options>& field : fields) {
    if (field.is_key) keys.push_back(prefix + std::string(field.name));
  }
  return keys;
}

}  // namespace attend
