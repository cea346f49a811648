#include "config/declared_options.h"

#include <type_traits>

#include "util/strings.h"

namespace attend {

void ReadDeclaredOptions(const ParamBlock& block, std::vector<DeclaredOption>* options) {
  for (DeclaredOption& option : *options) {
    std::visit(
        [&](auto& value) {
          using T = std::remove_cvref_t<decltype(value)>;
          if constexpr (std::is_same_v<T, bool>) {
            value = block.GetBool(option.key, value);
          } else if constexpr (std::is_same_v<T, int>) {
            value = block.GetInt(option.key, value);
          } else if constexpr (std::is_same_v<T, double>) {
            value = block.GetDouble(option.key, value);
          } else if constexpr (std::is_same_v<T, std::string>) {
            value = block.GetString(option.key, value);
          } else if constexpr (std::is_same_v<T, std::vector<std::string>>) {
            value = block.GetStrings(option.key, value);
          } else {
            value = block.GetDoubles(option.key, value);
          }
        },
        option.value);
  }
}

std::vector<FieldDescription> DescribeDeclaredOptions(const std::vector<DeclaredOption>& options) {
  std::vector<FieldDescription> lines;
  // Appends only: GCC 12 warns falsely (-Wrestrict) on chains of operator+.
  for (const DeclaredOption& option : options) {
    FieldDescription line;
    line.key = option.key;
    std::visit(
        [&](const auto& value) {
          using T = std::remove_cvref_t<decltype(value)>;
          if constexpr (std::is_same_v<T, bool>) {
            line.type = "bool";
            line.fallback = value ? "true" : "false";
          } else if constexpr (std::is_same_v<T, int>) {
            line.type = "int";
            line.fallback = std::to_string(value);
          } else if constexpr (std::is_same_v<T, double>) {
            line.type = "number";
            line.fallback = ShortestNumber(value);
          } else if constexpr (std::is_same_v<T, std::string>) {
            line.type = "text";
            line.fallback.append("\"").append(value).append("\"");
          } else if constexpr (std::is_same_v<T, std::vector<std::string>>) {
            line.type = "list";
            line.fallback.append("[").append(Join(value, ", ")).append("]");
          } else {
            line.type = "numbers";
            line.fallback = internal::NumbersText(value);
          }
        },
        option.value);
    lines.push_back(line);
  }
  return lines;
}

}  // namespace attend
