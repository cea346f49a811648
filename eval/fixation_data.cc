#include "eval/fixation_data.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>

#include "util/error.h"
#include "util/strings.h"

namespace attend {

namespace {

namespace fs = std::filesystem;

// The extensions a stimulus may have (compared in lower case).
const std::vector<std::string> kStimulusExtensions = {".jpg", ".jpeg", ".png",
                                                      ".ppm", ".pgm",  ".bmp"};

// Parses the whole token, so that "12abc" or "1.5" (as an integer) is rejected.
template <typename T>
bool ParseWhole(const std::string& token, T* value) {
  const char* end = token.data() + token.size();
  const auto [stop, error] = std::from_chars(token.data(), end, *value);
  return error == std::errc() && stop == end;
}

// The column (0-based) and unit of the durations, as the header line names them; nullopt-like
// {-1, 0} when it names none.
struct HeaderDuration {
  int column = -1;
  double seconds_per_unit = 0.0;
};

HeaderDuration DurationInHeader(const std::string& comment) {
  std::istringstream words(comment.substr(comment.find('#') + 1));
  int column = 0;
  for (std::string word; words >> word; ++column) {
    if (word == "duration_ms") return {column, 1e-3};
    if (word == "duration_s") return {column, 1.0};
  }
  return {};
}

// Parses one data line; the message of the returned error says what is wrong, "" when fine.
// `duration` is the column of the durations (-1: none) in `seconds_per_unit`.
std::string ParseLine(const std::string& line, const HeaderDuration& duration,
                      Fixation* fixation) {
  std::istringstream fields(line);
  std::vector<std::string> columns;
  const size_t wanted = std::max(3, duration.column + 1);
  for (std::string column; columns.size() < wanted && fields >> column;) columns.push_back(column);
  if (columns.size() < 3) {
    return "expected 'subject x y', got " + std::to_string(columns.size()) + " column(s)";
  }
  const std::string& subject = columns[0];
  const std::string& x = columns[1];
  const std::string& y = columns[2];
  long long subject_value = 0;
  if (!ParseWhole(subject, &subject_value)) return "subject '" + subject + "' is not an integer";
  if (subject_value < 0) return "subject " + subject + " is negative";
  if (subject_value > std::numeric_limits<int>::max())
    return "subject " + subject + " is too large";
  double x_value = 0.0, y_value = 0.0;
  if (!ParseWhole(x, &x_value)) return "x '" + x + "' is not a number";
  if (!ParseWhole(y, &y_value)) return "y '" + y + "' is not a number";
  if (!std::isfinite(x_value)) return "x '" + x + "' is not finite";
  if (!std::isfinite(y_value)) return "y '" + y + "' is not finite";
  fixation->subject = static_cast<int>(subject_value);
  // The file counts pixels from 1 (MATLAB); attend from 0.
  fixation->x = x_value - 1.0;
  fixation->y = y_value - 1.0;
  if (duration.column >= 0) {
    const std::string where = "column " + std::to_string(duration.column + 1);
    if (static_cast<int>(columns.size()) <= duration.column) return "no duration in " + where;
    const std::string& text = columns[duration.column];
    double value = 0.0;
    if (!ParseWhole(text, &value) || !std::isfinite(value)) {
      return "duration '" + text + "' (" + where + ") is not a finite number";
    }
    if (value < 0.0) return "duration " + text + " (" + where + ") is negative";
    fixation->duration_s = value * duration.seconds_per_unit;
  }
  return "";
}

// Files of `folder` by stem whose lower-case extension is one of `extensions`.
std::map<std::string, fs::path> FilesByStem(const fs::path& folder,
                                            const std::vector<std::string>& extensions) {
  std::map<std::string, fs::path> files;
  for (const fs::directory_entry& entry : fs::directory_iterator(folder)) {
    if (!entry.is_regular_file()) continue;
    const std::string extension = Lowercase(entry.path().extension().string());
    if (std::find(extensions.begin(), extensions.end(), extension) == extensions.end()) continue;
    const std::string stem = entry.path().stem().string();
    const auto [it, inserted] = files.emplace(stem, entry.path());
    if (!inserted) {
      throw InputError(folder.string() + ": two files for id " + stem + " (" +
                       it->second.filename().string() + ", " + entry.path().filename().string() +
                       ")");
    }
  }
  return files;
}

}  // namespace

std::vector<Fixation> ReadFixationFile(const std::string& path, const DurationColumn& durations) {
  // An ifstream opens a folder without complaint and then reads nothing.
  if (fs::is_directory(path)) throw InputError(path + ": is a folder, not a fixation file");
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot read the fixation file");
  HeaderDuration duration;
  if (durations.source == DurationColumn::Source::kColumn) {
    ATTEND_CHECK(durations.column >= 3 && durations.seconds_per_unit > 0.0);
    duration = {durations.column, durations.seconds_per_unit};
  }
  const bool from_header = durations.source == DurationColumn::Source::kHeader;
  std::vector<Fixation> fixations;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    const size_t first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos) continue;
    if (line[first] == '#') {
      // The header: comments before the first data line; the first to name a duration wins.
      if (from_header && fixations.empty() && duration.column < 0) {
        duration = DurationInHeader(line);
        if (duration.column >= 0 && duration.column < 3) {
          throw InputError(path + ":" + std::to_string(number) +
                           ": the header names column " + std::to_string(duration.column + 1) +
                           " the duration, but columns 1-3 are subject x y");
        }
      }
      continue;
    }
    Fixation fixation;
    const std::string problem = ParseLine(line, duration, &fixation);
    if (!problem.empty()) throw InputError(path + ":" + std::to_string(number) + ": " + problem);
    fixations.push_back(fixation);
  }
  if (in.bad()) throw InputError(path + ": cannot read the fixation file");
  return fixations;
}

std::vector<SubjectFixations> GroupBySubject(const std::vector<Fixation>& fixations) {
  std::map<int, std::vector<Fixation>> by_subject;
  for (const Fixation& f : fixations) by_subject[f.subject].push_back(f);
  std::vector<SubjectFixations> groups;
  for (auto& [subject, list] : by_subject) groups.push_back({subject, std::move(list)});
  return groups;
}

FixationDataset OpenFixationDataset(const std::string& dir) {
  const fs::path root(dir);
  if (!fs::is_directory(root)) throw InputError(dir + ": no such folder");
  if (!fs::is_directory(root / "stimuli")) throw InputError(dir + ": no stimuli/ folder");
  if (!fs::is_directory(root / "fixations")) throw InputError(dir + ": no fixations/ folder");
  const std::map<std::string, fs::path> stimuli =
      FilesByStem(root / "stimuli", kStimulusExtensions);
  const std::map<std::string, fs::path> fixations = FilesByStem(root / "fixations", {".txt"});

  FixationDataset dataset;
  dataset.dir = dir;
  for (const auto& [id, stimulus] : stimuli) {  // std::map: sorted by id
    const auto match = fixations.find(id);
    if (match == fixations.end()) {
      ++dataset.skipped;
      continue;
    }
    dataset.items.push_back({id, stimulus.string(), match->second.string()});
  }
  dataset.skipped += static_cast<int>(fixations.size() - dataset.items.size());
  if (dataset.items.empty()) throw InputError(dir + ": no stimulus has a fixation file");
  return dataset;
}

}  // namespace attend
