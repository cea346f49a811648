#include "io/tracking_files.h"

#include <cmath>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "io/text_fields.h"
#include "util/error.h"
#include "util/file_checks.h"
#include "util/limits.h"
#include "util/strings.h"

namespace attend {

namespace {

constexpr const char* kTracksCsvHeader = "frame,id,x,y,w,h,state";

std::string Where(const std::string& path, int line) { return path + ":" + std::to_string(line); }

int ParseInteger(const std::string& text, const std::string& path, int line, const char* field) {
  const double value = ParseWholeField(text, path, line, field);
  // Checked before the conversion to int, which would overflow.
  if (std::fabs(value) > std::numeric_limits<int>::max()) {
    throw InputError(Where(path, line) + ": " + field + " number out of range: '" + text + "'");
  }
  return static_cast<int>(value);
}

}  // namespace

std::vector<TrackRow> ReadTracksCsv(const std::string& path) {
  RequireRegularFile(path, "the tracks file", ExitStatus::kBadInput);
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot read the tracks file");
  std::vector<TrackRow> rows;
  RowsOnce once;  // a target with two rows in one frame would be scored twice
  std::string text;
  int line = 0;
  bool header = false;
  while (std::getline(in, text)) {
    ++line;
    text = TrimField(text);
    if (text.empty()) continue;
    if (!header) {
      if (text != kTracksCsvHeader) {
        throw InputError(Where(path, line) + ": expected the header '" + kTracksCsvHeader +
                         "', got '" + text + "'");
      }
      header = true;
      continue;
    }
    std::vector<std::string> fields = Split(text, ',');
    if (fields.size() != 7) {
      throw InputError(Where(path, line) + ": expected 7 fields (" + kTracksCsvHeader + "), got " +
                       std::to_string(fields.size()));
    }
    for (std::string& field : fields) field = TrimField(field);
    TrackRow row;
    row.frame = ParseInteger(fields[0], path, line, "frame");
    row.id = ParseInteger(fields[1], path, line, "id");
    row.box.x = ParseNumberField(fields[2], path, line, "x");
    row.box.y = ParseNumberField(fields[3], path, line, "y");
    row.box.width = ParseNumberField(fields[4], path, line, "w");
    row.box.height = ParseNumberField(fields[5], path, line, "h");
    row.state = fields[6];
    if (row.frame < 0 || row.frame > kMaxFrameNumber) {
      throw InputError(Where(path, line) + ": frame number out of range: '" + fields[0] +
                       "' (must be in 0.." + std::to_string(kMaxFrameNumber) + ")");
    }
    if (row.id < 0 || row.id > kMaxId) {
      throw InputError(Where(path, line) + ": id out of range: '" + fields[1] +
                       "' (must be in 0.." + std::to_string(kMaxId) + ")");
    }
    if (row.box.width < 0.0 || row.box.height < 0.0) {
      throw InputError(Where(path, line) + ": w and h must be >= 0");
    }
    if (row.state != "found" && row.state != "occluded" && row.state != "lost") {
      throw InputError(Where(path, line) + ": state must be found, occluded or lost, got '" +
                       row.state + "'");
    }
    once.Add(row.frame, row.id, path, line, "target");
    rows.push_back(row);
  }
  if (!header) throw InputError(path + ": empty; expected the header '" + kTracksCsvHeader + "'");
  return rows;
}

void WriteTracksCsv(const std::string& path, const std::vector<TrackRow>& rows) {
  std::ofstream out(path);
  if (!out) throw OutputError(path + ": cannot write the tracks file");
  out << kTracksCsvHeader << "\n";
  out.precision(17);
  for (const TrackRow& row : rows) {
    out << row.frame << "," << row.id << "," << row.box.x << "," << row.box.y << ","
        << row.box.width << "," << row.box.height << "," << row.state << "\n";
  }
  out.close();
  if (!out) throw OutputError(path + ": error while writing the tracks file");
}

std::vector<cv::Rect2d> ReadOtbGroundTruth(const std::string& path) {
  RequireRegularFile(path, "the ground-truth file", ExitStatus::kBadInput);
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot read the ground-truth file");
  std::vector<std::string> lines;
  std::string text;
  while (std::getline(in, text)) lines.push_back(TrimField(text));
  while (!lines.empty() && lines.back().empty()) lines.pop_back();
  if (lines.empty()) throw InputError(path + ": no boxes (expected one 'x y w h' a line)");

  std::vector<cv::Rect2d> boxes;
  boxes.reserve(lines.size());
  for (size_t i = 0; i < lines.size(); ++i) {
    const int line = static_cast<int>(i) + 1;
    // Fields are separated by any run of tabs, spaces and commas.
    std::vector<std::string> fields;
    std::string field;
    for (const char c : lines[i] + " ") {
      if (c == ' ' || c == '\t' || c == ',') {
        if (!field.empty()) fields.push_back(field);
        field.clear();
      } else {
        field += c;
      }
    }
    if (fields.size() != 4) {
      throw InputError(Where(path, line) + ": expected 4 numbers 'x y w h', got " +
                       std::to_string(fields.size()) + " field(s)" +
                       (fields.empty() ? " (an empty line: frame " + std::to_string(line - 1) +
                                             " would have no box)"
                                       : ""));
    }
    const char* names[] = {"x", "y", "w", "h"};
    double value[4];
    for (int k = 0; k < 4; ++k) value[k] = ParseNumberField(fields[k], path, line, names[k], true);
    if (value[2] < 0.0 || value[3] < 0.0) {
      throw InputError(Where(path, line) + ": w and h must be >= 0");
    }
    const bool missing = std::isnan(value[0]) || std::isnan(value[1]) || std::isnan(value[2]) ||
                         std::isnan(value[3]) || value[2] == 0.0 || value[3] == 0.0;
    boxes.push_back(missing ? cv::Rect2d()
                            : cv::Rect2d(value[0] - 1.0, value[1] - 1.0, value[2], value[3]));
  }
  return boxes;
}

}  // namespace attend
