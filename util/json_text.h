// JSON text that is always valid UTF-8, and numbers that may be unknown. nlohmann-json throws type_error 316 on a string that is
// not UTF-8 (a path or a configuration value from outside); attend writes such bytes as U+FFFD
// instead, so that a record or report is never lost to one bad byte.
#pragma once

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>

namespace attend {

// `value` as a JSON number, or null when it is not finite (an unknown or undefined measure).
inline nlohmann::ordered_json FiniteOrNull(double value) {
  return std::isfinite(value) ? nlohmann::ordered_json(value) : nlohmann::ordered_json();
}

// `value.dump(indent)` with invalid UTF-8 replaced; -1: one line.
template <typename Json>
std::string JsonText(const Json& value, int indent = -1) {
  return value.dump(indent, ' ', false, Json::error_handler_t::replace);
}

}  // namespace attend
