#include "io/text_fields.h"

#include <cmath>
#include <exception>

#include "util/error.h"
#include "util/limits.h"

namespace attend {

std::string TrimField(const std::string& text) {
  const size_t begin = text.find_first_not_of(" \t\r");
  if (begin == std::string::npos) return "";
  const size_t end = text.find_last_not_of(" \t\r");
  return text.substr(begin, end - begin + 1);
}

double ParseNumberField(const std::string& text, const std::string& path, int line,
                        const char* field, bool allow_nan) {
  try {
    size_t used = 0;
    const double value = std::stod(text, &used);
    if (used == text.size() && (std::isfinite(value) || (allow_nan && std::isnan(value)))) {
      return value;
    }
  } catch (const std::exception&) {
  }
  throw InputError(path + ":" + std::to_string(line) + ": field '" + field +
                   "' is not a number: '" + text + "'");
}

double ParseWholeField(const std::string& text, const std::string& path, int line,
                       const char* field) {
  const double value = ParseNumberField(text, path, line, field);
  if (value != std::floor(value)) {
    throw InputError(path + ":" + std::to_string(line) + ": field '" + field +
                     "' is not an integer: '" + text + "'");
  }
  return value;
}

void RowsOnce::Add(int frame, int id, const std::string& path, int line, const char* what) {
  const auto [at, added] = lines_.emplace(std::make_pair(frame, id), line);
  if (added) {
    if (++per_frame_[frame] > kMaxTargetsPerRecord) {
      throw InputError(path + ":" + std::to_string(line) + ": more than " +
                       std::to_string(kMaxTargetsPerRecord) + " " + what + "s in frame " +
                       std::to_string(frame) + " (docs/LIMITS.md)");
    }
    return;
  }
  throw InputError(path + ":" + std::to_string(line) + ": " + what + " " + std::to_string(id) +
                   " again in frame " + std::to_string(frame) + " (line " +
                   std::to_string(at->second) + " has it too)");
}

}  // namespace attend
