#include "util/frame_range.h"

#include <stdexcept>

#include "util/error.h"

namespace attend {

FrameRange ParseFrameRange(const std::string& text, FrameRange range) {
  const size_t colon = text.find(':');
  if (colon == std::string::npos) {
    throw ConfigError("--frames " + text + ": expected FIRST:LAST (for example 10:50 or 10:)");
  }
  auto parse = [&](const std::string& part, int* value) {
    if (part.empty()) return;
    try {
      size_t used = 0;
      *value = std::stoi(part, &used);
      if (used != part.size() || *value < 0) throw std::invalid_argument(part);
    } catch (const std::exception&) {
      throw ConfigError("--frames " + text + ": expected FIRST:LAST with non-negative integers");
    }
  };
  parse(text.substr(0, colon), &range.first);
  parse(text.substr(colon + 1), &range.last);
  if (range.last >= 0 && range.last < range.first) {
    throw ConfigError("--frames " + text + ": the range ends (" + std::to_string(range.last) +
                      ") before it starts (" + std::to_string(range.first) + ")");
  }
  return range;
}

}  // namespace attend
