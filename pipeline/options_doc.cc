#include "pipeline/options_doc.h"

#include <fstream>
#include <sstream>

#include "features/builtin.h"
#include "pipeline/options_io.h"
#include "tracker/target_tracker.h"
#include "util/error.h"
#include "util/strings.h"

namespace attend {

namespace {

constexpr const char* kBegin = "<!-- options: ";
constexpr const char* kEnd = "<!-- end options -->";

// `text` for a markdown table cell: a `|` would end the cell.
std::string Cell(const std::string& text) {
  std::string cell;
  for (const char c : text) {
    if (c == '|') cell += '\\';
    cell += c;
  }
  return cell;
}

// "`a`, `b`" of "a|b".
std::string Names(const std::string& alternatives) {
  std::vector<std::string> names;
  for (const std::string& name : Split(alternatives, '|')) names.push_back("`" + name + "`");
  return Join(names, ", ");
}

// The doc of a tracker key, led by the kinds that read it when not all of them do ("kinds:
// bip. "), unless the doc starts with them already ("kcf: ...").
std::string WithKinds(const std::string& key, const std::string& doc) {
  std::vector<std::string> kinds;
  for (const TrackerKindInfo& info : TrackerKinds()) {
    if (info.uses_key(key)) kinds.emplace_back(info.name);
  }
  if (kinds.empty() || kinds.size() == TrackerKinds().size()) return doc;
  if (doc.rfind(Join(kinds, ", ") + ":", 0) == 0) return doc;
  return "kinds: " + Join(kinds, ", ") + ". " + doc;
}

// One row: key, type, default, range (or choices), doc.
std::string Row(const FieldDescription& line, const std::string& doc) {
  std::string type = line.type;
  std::string range = line.range;
  if (range.rfind("must be ", 0) == 0) range = range.substr(8);
  if (range.rfind("in ", 0) == 0) range = range.substr(3);
  if (range == "a finite number") range = "";
  if (type.rfind("list of ", 0) == 0 && type != "list of features") {
    range = "each of " + Names(type.substr(8));
    type = "list";
  } else if (type.find('|') != std::string::npos) {
    range = Names(type);
    type = "choice";
  }
  // Appends only: GCC 12 warns falsely (-Wrestrict) on chains of operator+.
  std::string key, fallback;
  key.append("`").append(line.key).append("`");
  fallback.append("`").append(Cell(line.fallback)).append("`");
  std::string row = "|";
  for (const std::string& cell : {key, type, fallback, Cell(range), Cell(doc)}) {
    if (!cell.empty()) row.append(" ").append(cell);
    row.append(" |");
  }
  return row.append("\n");
}

std::string Header() {
  return "| key | type | default | range | meaning |\n|---|---|---|---|---|\n";
}

std::string FeatureTable() {
  std::string table = Header();
  for (const BuiltinFeature& feature : BuiltinFeatureTable()) {
    const std::string name = feature.name;
    table.append("| `features.").append(name).append("` | feature | | | ");
    table.append(Cell(feature.summary)).append(" |\n");
    for (FieldDescription line : feature.keys()) {
      line.key = std::string("features.").append(name).append(".").append(line.key);
      table += Row(line, line.doc);
    }
  }
  return table;
}

}  // namespace

std::vector<FieldDescription> DescribeFeatureKeys() {
  std::vector<FieldDescription> lines;
  for (const BuiltinFeature& feature : BuiltinFeatureTable()) {
    for (FieldDescription line : feature.keys()) {
      line.key = std::string("features.").append(feature.name).append(".").append(line.key);
      lines.push_back(line);
    }
  }
  return lines;
}

std::vector<FieldDescription> DescribeEveryKey() {
  std::vector<FieldDescription> lines = DescribeConfiguration();
  const std::vector<FieldDescription> features = DescribeFeatureKeys();
  lines.insert(lines.end(), features.begin(), features.end());
  return lines;
}

std::string OptionTable(const std::string& section) {
  if (section == "features") return FeatureTable();
  std::string rows;
  for (const FieldDescription& line : DescribeConfiguration()) {
    const std::string key_section = line.key.substr(0, line.key.find('.'));
    if (key_section != section || line.type == "list of features") continue;
    const std::string name = line.key.substr(line.key.find('.') + 1);
    rows += Row(line, section == "tracker" ? WithKinds(name, line.doc) : line.doc);
  }
  if (rows.empty()) throw ConfigError("no configuration section '" + section + "'");
  return Header() + rows;
}

std::string WithGeneratedTables(const std::string& text) {
  std::istringstream in(text);
  std::string out;
  std::string line;
  int number = 0;
  int begin_line = 0;
  bool inside = false;
  while (std::getline(in, line)) {
    ++number;
    if (!inside) {
      out += line + "\n";
      if (line.rfind(kBegin, 0) == 0) {
        const size_t end = line.find(" -->");
        if (end == std::string::npos) {
          throw ConfigError("line " + std::to_string(number) + ": expected " + kBegin +
                            "SECTION -->");
        }
        const std::string section = line.substr(std::string(kBegin).size(),
                                                end - std::string(kBegin).size());
        try {
          out += OptionTable(section);
        } catch (const ConfigError& e) {
          throw ConfigError("line " + std::to_string(number) + ": " + e.what());
        }
        inside = true;
        begin_line = number;
      }
    } else if (line == kEnd) {
      out += line + "\n";
      inside = false;
    }
  }
  if (inside) {
    throw ConfigError("line " + std::to_string(begin_line) + ": no " + kEnd + " after it");
  }
  return out;
}

bool WriteGeneratedTables(const std::string& path) {
  std::ifstream file(path);
  if (!file) throw ConfigError(path + ": cannot read the file");
  std::stringstream text;
  text << file.rdbuf();
  std::string generated;
  try {
    generated = WithGeneratedTables(text.str());
  } catch (const ConfigError& e) {
    throw ConfigError(path + ": " + e.what());
  }
  if (generated == text.str()) return false;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << generated;
  if (!out) throw ConfigError(path + ": cannot write the file");
  return true;
}

}  // namespace attend
