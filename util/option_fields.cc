#include "util/option_fields.h"

#include <algorithm>

namespace attend {

std::string FormatFieldDescriptions(const std::vector<FieldDescription>& lines,
                                    const std::string& prefix) {
  size_t width = 0;
  for (const FieldDescription& line : lines)
    width = std::max(width, prefix.size() + line.key.size());
  // Appends only: GCC 12 warns falsely (-Wrestrict) on chains of operator+.
  std::string text;
  for (const FieldDescription& line : lines) {
    const std::string key = prefix + line.key;
    text.append("  ").append(key).append(width - key.size() + 2, ' ').append(line.type);
    if (!line.range.empty()) text.append(" ").append(line.range.substr(line.range.find("be ") + 3));
    text.append(", default ").append(line.fallback).append(": ").append(line.doc).append("\n");
  }
  return text;
}

}  // namespace attend
