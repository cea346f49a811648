// Reads the fields of an options struct (util/option_fields.h) from a ParamBlock: each key
// with its field's range or choices, starting from the struct's current values, so an error
// names the key and its line.
#pragma once

#include <algorithm>
#include <string>
#include <type_traits>
#include <vector>

#include "config/param_block.h"
#include "util/option_fields.h"
#include "util/strings.h"

namespace attend {

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
      } else if constexpr (std::is_arithmetic_v<T>) {
        value = static_cast<T>(block.GetDouble(key, value, field.range));
      } else if constexpr (std::is_same_v<T, std::string>) {
        value = field.choices ? block.GetChoice(key, value, field.choices())
                              : block.GetString(key, value);
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
    } else {
      const std::string name = block.GetChoice(key, member.get(*options), member.names());
      member.set(options, name);
    }
  });
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
