#include "io/ground_truth.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "io/text_fields.h"
#include "util/error.h"
#include "util/file_checks.h"
#include "util/limits.h"
#include "util/strings.h"

namespace attend {

namespace {

// An integer in [0, max] (checked before the conversion to int, which would overflow).
int ParseInteger(const std::string& text, const std::string& path, int line, const char* field,
                 int max) {
  const double value = ParseWholeField(text, path, line, field);
  if (value < 0 || value > max) {
    throw InputError(path + ":" + std::to_string(line) + ": " + field + " number out of range: '" +
                     text + "' (must be in 0.." + std::to_string(max) + ")");
  }
  return static_cast<int>(value);
}

}  // namespace

bool IsGroundTruthKind(const std::string& kind) {
  return kind == "object" || kind == "skin" || kind == "car" || kind == "person" ||
         kind == "cyclist";
}

std::vector<GtObject> ReadObjectsCsv(const std::string& path) {
  RequireRegularFile(path, "the ground-truth file", ExitStatus::kBadInput);
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot read the ground-truth file");
  std::vector<GtObject> objects;
  // An object boxed twice in one frame would be scored as two objects, one never attended.
  RowsOnce rows;
  std::string text;
  int line = 0;
  while (std::getline(in, text)) {
    ++line;
    text = TrimField(text);
    if (text.empty()) continue;
    if (line == 1 && text.rfind("frame", 0) == 0) continue;  // header
    std::vector<std::string> fields = Split(text, ',');
    if (fields.size() != 9) {
      throw InputError(path + ":" + std::to_string(line) + ": expected 9 fields (" +
                       kObjectsCsvHeader + "), got " + std::to_string(fields.size()));
    }
    for (std::string& field : fields) field = TrimField(field);
    GtObject object;
    object.frame = ParseInteger(fields[0], path, line, "frame", kMaxFrameNumber);
    object.id = ParseInteger(fields[1], path, line, "id", kMaxId);
    object.box.x = ParseNumberField(fields[2], path, line, "x");
    object.box.y = ParseNumberField(fields[3], path, line, "y");
    object.box.width = ParseNumberField(fields[4], path, line, "w");
    object.box.height = ParseNumberField(fields[5], path, line, "h");
    object.visible_fraction = ParseNumberField(fields[6], path, line, "visible_fraction");
    if (!fields[7].empty()) object.disparity = ParseNumberField(fields[7], path, line, "disparity");
    object.kind = fields[8];
    if (object.box.width < 0 || object.box.height < 0 || object.visible_fraction < 0 ||
        object.visible_fraction > 1) {
      throw InputError(path + ":" + std::to_string(line) +
                       ": negative size, or visible_fraction outside [0, 1]");
    }
    if (!IsGroundTruthKind(object.kind)) {
      throw InputError(path + ":" + std::to_string(line) +
                       ": kind must be object, skin, car, person or cyclist, got '" +
                       object.kind + "'");
    }
    rows.Add(object.frame, object.id, path, line, "object");
    objects.push_back(object);
  }
  return objects;
}

void WriteObjectsCsv(const std::string& path, const std::vector<GtObject>& objects) {
  std::ofstream out(path);
  if (!out) throw OutputError(path + ": cannot write the ground-truth file");
  out << kObjectsCsvHeader << "\n";
  out.precision(17);
  for (const GtObject& o : objects) {
    out << o.frame << "," << o.id << "," << o.box.x << "," << o.box.y << "," << o.box.width << ","
        << o.box.height << "," << o.visible_fraction << ",";
    if (o.disparity.has_value()) out << *o.disparity;
    out << "," << o.kind << "\n";
  }
  if (!out) throw OutputError(path + ": error while writing the ground-truth file");
}

std::string FrameStem(int index) {
  char stem[16];
  std::snprintf(stem, sizeof(stem), "%06d", index);
  return stem;
}

std::string GtDisparityPath(const std::string& sequence_folder, int frame) {
  return (std::filesystem::path(sequence_folder) / "gt" / "disparity" / (FrameStem(frame) + ".pfm"))
      .string();
}

}  // namespace attend
