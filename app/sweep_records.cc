#include "app/sweep_records.h"

#include <sys/statvfs.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <limits>

#include "util/error.h"
#include "util/file_checks.h"
#include "util/json_text.h"

namespace attend {

namespace {

using Json = nlohmann::ordered_json;

// What a value is, for messages: `the string "zero"`, `the number 3.5`, `an array`, ...
std::string Found(const Json& value) {
  std::string text;
  switch (value.type()) {
    case Json::value_t::string:
      text = JsonText(value);
      if (text.size() > 42) text = text.substr(0, 40) + "...\"";
      return "the string " + text;
    case Json::value_t::number_integer:
    case Json::value_t::number_unsigned:
    case Json::value_t::number_float:
      return "the number " + JsonText(value);
    case Json::value_t::boolean:
      return value.get<bool>() ? "true" : "false";
    case Json::value_t::array:
      return "an array";
    case Json::value_t::object:
      return "an object";
    case Json::value_t::null:
      return "null";
    default:
      return "a value of another kind";
  }
}

std::string Expected(const std::string& what, const Json& value) {
  return "expected " + what + ", found " + Found(value);
}

}  // namespace

std::string WhyUnwritable(const std::string& folder) {
  struct statvfs space {};
  if (::statvfs(folder.c_str(), &space) == 0 && space.f_bavail == 0) return "the disk is full";
  if (::access(folder.c_str(), W_OK) != 0) return std::strerror(errno);
  return "";
}

SweepRecord::SweepRecord(const std::string& text, std::string file) : file_(std::move(file)) {
  try {
    json_ = Json::parse(text);
  } catch (const nlohmann::json::exception& e) {
    std::string reason = e.what();
    // "[json.exception.parse_error.101] parse error at line 1, column 2: ..." less its tag.
    const std::size_t tag = reason.find("] ");
    if (tag != std::string::npos) reason = reason.substr(tag + 2);
    throw InputError(file_ + ": not valid JSON (" + reason + ")");
  }
  if (!json_.is_object()) throw InputError(file_ + ": " + Expected("a JSON object", json_));
}

SweepRecord::SweepRecord(Json json, std::string file, std::string path)
    : json_(std::move(json)), file_(std::move(file)), path_(std::move(path)) {}

SweepRecord SweepRecord::Load(const std::string& file) {
  return SweepRecord(
      ReadRegularFile(file, "the sweep record", ExitStatus::kBadInput, kMaxSweepRecordBytes), file);
}

std::string SweepRecord::KeyPath(const std::string& key) const {
  return path_.empty() ? key : path_ + "." + key;
}

void SweepRecord::Fail(const std::string& key, const std::string& message) const {
  std::string path = KeyPath(key);
  if (path.size() > 80) path = path.substr(0, 77) + "...";  // a key of megabytes, cut
  throw InputError(file_ + ": " + path + ": " + message);
}

bool SweepRecord::Has(const std::string& key) const { return json_.contains(key); }

const Json& SweepRecord::Field(const std::string& key) const {
  const auto found = json_.find(key);
  if (found == json_.end()) Fail(key, "missing");
  return *found;
}

std::string SweepRecord::String(const std::string& key) const {
  const Json& value = Field(key);
  if (!value.is_string()) Fail(key, Expected("a string", value));
  return value.get<std::string>();
}

std::string SweepRecord::String(const std::string& key, const std::string& absent) const {
  return Has(key) ? String(key) : absent;
}

long SweepRecord::Integer(const std::string& key, long min, long max) const {
  const Json& value = Field(key);
  if (!value.is_number_integer()) Fail(key, Expected("an integer", value));
  // Unsigned values above the range of long wrap: compared as what they are.
  if (value.is_number_unsigned() &&
      value.get<std::uint64_t>() > static_cast<std::uint64_t>(std::numeric_limits<long>::max())) {
    Fail(key, JsonText(value) + " out of range [" + std::to_string(min) + ", " +
                  std::to_string(max) + "]");
  }
  const long number = value.get<long>();
  if (number < min || number > max) {
    Fail(key, std::to_string(number) + " out of range [" + std::to_string(min) + ", " +
                  std::to_string(max) + "]");
  }
  return number;
}

long SweepRecord::Integer(const std::string& key, long min, long max, long absent) const {
  return Has(key) ? Integer(key, min, max) : absent;
}

double SweepRecord::Number(const std::string& key, double absent) const {
  if (!Has(key)) return absent;
  const Json& value = Field(key);
  if (!value.is_number()) Fail(key, Expected("a number", value));
  const double number = value.get<double>();
  if (!std::isfinite(number) || number < 0) Fail(key, Expected("a number >= 0", value));
  return number;
}

std::vector<std::string> SweepRecord::Strings(const std::string& key) const {
  const Json& value = Field(key);
  if (!value.is_array()) Fail(key, Expected("a list of strings", value));
  std::vector<std::string> strings;
  for (std::size_t i = 0; i < value.size(); ++i) {
    if (!value[i].is_string()) {
      Fail(key + "[" + std::to_string(i) + "]", Expected("a string", value[i]));
    }
    strings.push_back(value[i].get<std::string>());
  }
  return strings;
}

std::vector<std::vector<std::string>> SweepRecord::StringLists(const std::string& key) const {
  const Json& value = Field(key);
  if (!value.is_array()) Fail(key, Expected("a list of lists of strings", value));
  std::vector<std::vector<std::string>> lists;
  for (std::size_t i = 0; i < value.size(); ++i) {
    const std::string item = key + "[" + std::to_string(i) + "]";
    if (!value[i].is_array()) Fail(item, Expected("a list of strings", value[i]));
    lists.emplace_back();
    for (std::size_t j = 0; j < value[i].size(); ++j) {
      const Json& word = value[i][j];
      if (!word.is_string()) Fail(item + "[" + std::to_string(j) + "]", Expected("a string", word));
      lists.back().push_back(word.get<std::string>());
    }
  }
  return lists;
}

std::vector<std::vector<int>> SweepRecord::IntLists(
    const std::string& key, const std::vector<std::vector<int>>& absent) const {
  if (!Has(key)) return absent;
  const Json& value = Field(key);
  if (!value.is_array()) Fail(key, Expected("a list of lists of integers", value));
  std::vector<std::vector<int>> lists;
  for (std::size_t i = 0; i < value.size(); ++i) {
    const std::string item = key + "[" + std::to_string(i) + "]";
    if (!value[i].is_array()) Fail(item, Expected("a list of integers", value[i]));
    lists.emplace_back();
    for (std::size_t j = 0; j < value[i].size(); ++j) {
      const Json& number = value[i][j];
      if (!number.is_number_integer() || number.get<long>() < 0 || number.get<long>() > 1000000) {
        Fail(item + "[" + std::to_string(j) + "]", Expected("an integer in [0, 1000000]", number));
      }
      lists.back().push_back(number.get<int>());
    }
  }
  return lists;
}

std::vector<std::pair<std::string, std::string>> SweepRecord::StringMap(
    const std::string& key) const {
  const Json& value = Field(key);
  if (!value.is_object()) Fail(key, Expected("a map of strings", value));
  std::vector<std::pair<std::string, std::string>> map;
  for (const auto& [name, entry] : value.items()) {
    if (!entry.is_string()) Fail(key + "." + name, Expected("a string", entry));
    map.emplace_back(name, entry.get<std::string>());
  }
  return map;
}

SweepRecord SweepRecord::Object(const std::string& key) const {
  const Json& value = Field(key);
  if (!value.is_object()) Fail(key, Expected("an object", value));
  return SweepRecord(value, file_, KeyPath(key));
}

std::vector<SweepRecord> SweepRecord::Objects(const std::string& key) const {
  const Json& value = Field(key);
  if (!value.is_array()) Fail(key, Expected("a list of objects", value));
  std::vector<SweepRecord> objects;
  for (std::size_t i = 0; i < value.size(); ++i) {
    const std::string item = key + "[" + std::to_string(i) + "]";
    if (!value[i].is_object()) Fail(item, Expected("an object", value[i]));
    objects.push_back(SweepRecord(value[i], file_, KeyPath(item)));
  }
  return objects;
}

CellStatus ParseCellStatus(const std::string& text, const std::string& file) {
  const SweepRecord record(text, file);
  CellStatus status;
  const std::string state = record.String("state");
  if (state == "running") {
    status.state = CellState::kRunning;
  } else if (state == "done") {
    status.state = CellState::kDone;
  } else if (state == "failed") {
    status.state = CellState::kFailed;
  } else if (state == "killed") {
    status.state = CellState::kKilled;
  } else if (state == "interrupted") {
    status.state = CellState::kInterrupted;
  } else {
    record.Fail("state", "unknown state " + JsonText(Json(state)) +
                             " (running, done, failed, killed or interrupted)");
  }
  // Exit statuses of attend and of a process killed by a signal (128 + N).
  status.exit_status = static_cast<int>(record.Integer("exit_status", 0, 255, 0));
  status.message = record.String("message", "");
  status.seconds = record.Number("seconds", 0.0);
  status.host = record.String("host", "");
  status.pid = record.Integer("pid", 0, std::numeric_limits<int>::max(), 0);
  status.executor = record.String("executor", "");
  if (!status.executor.empty() && status.executor != "local" && status.executor != "slurm") {
    record.Fail("executor", "unknown executor " + JsonText(Json(status.executor)) +
                                " (local or slurm)");
  }
  status.slurm_task = record.String("slurm_task", "");
  return status;
}

std::vector<std::pair<std::string, double>> ParseCellScores(const std::string& text,
                                                            const std::string& file) {
  const SweepRecord record(text, file);
  std::vector<std::pair<std::string, double>> scores;
  for (const auto& [key, value] : record.json().items()) {
    if (value.is_null()) {
      scores.emplace_back(key, std::nan(""));
    } else if (value.is_number()) {
      scores.emplace_back(key, value.get<double>());
    } else {
      record.Fail(key, Expected("a number or null (a score)", value));
    }
  }
  return scores;
}

}  // namespace attend
