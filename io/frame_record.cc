#include "io/frame_record.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <stdexcept>

#include "util/error.h"
#include "util/file_checks.h"
#include "util/json_text.h"
#include "util/limits.h"

namespace attend {

namespace {

// [begin, end) of one axis from working into input pixels, clipped to [0, limit].
void InputFromWorkingSpan(int begin, int length, double scale, int limit, int* out_begin,
                          int* out_length) {
  int first = static_cast<int>(std::lround(begin / scale));
  int last = static_cast<int>(std::lround((begin + length) / scale));
  first = std::clamp(first, 0, limit);
  last = std::clamp(last, 0, limit);
  if (length > 0 && last <= first) {
    // Enlarging the input (scale > 1) can round a 1-px span to nothing; keep one pixel.
    if (first < limit) {
      last = first + 1;
    } else {
      first = std::max(0, limit - 1);
      last = limit;
    }
  }
  *out_begin = first;
  *out_length = std::max(0, last - first);
}

}  // namespace

cv::Rect InputFromWorkingBox(const cv::Rect& box_in_working, double scale_x, double scale_y,
                             cv::Size input_size) {
  ATTEND_CHECK(scale_x > 0.0 && scale_y > 0.0) << "scales must be positive";
  cv::Rect box;
  InputFromWorkingSpan(box_in_working.x, box_in_working.width, scale_x, input_size.width, &box.x,
                       &box.width);
  InputFromWorkingSpan(box_in_working.y, box_in_working.height, scale_y, input_size.height, &box.y,
                       &box.height);
  return box;
}

FrameRecord InputFromWorking(const FrameRecord& record_in_working, double scale_x, double scale_y,
                             cv::Size input_size) {
  FrameRecord record = record_in_working;
  const double area_scale = scale_x * scale_y;
  for (TargetRecord& target : record.targets) {
    target.bbox = InputFromWorkingBox(target.bbox, scale_x, scale_y, input_size);
    if (target.area > 0) {
      target.area = std::max(1, static_cast<int>(std::lround(target.area / area_scale)));
    }
    // Disparities are horizontal: they scale with the width.
    target.disparity_px /= scale_x;
    target.disparity_sd_px /= scale_x;
  }
  return record;
}

int VisibleTargets(const FrameRecord& record) {
  int n = 0;
  for (const TargetRecord& t : record.targets) n += Visible(t.state);
  return n;
}

namespace {

// `value` to a multiple of `step` (records keep what the estimates can tell); non-finite
// values (an unknown standard deviation) as null.
nlohmann::ordered_json Rounded(double value, double step) {
  if (!std::isfinite(value)) return nullptr;
  // Divided by the whole number 1 / step, the result is the double nearest the rounded
  // decimal, which prints as that decimal (21.15, not 21.150000000000002).
  const double per_unit = std::round(1.0 / step);
  return std::round(value * per_unit) / per_unit;
}

nlohmann::ordered_json Rounded3(const cv::Vec3d& v, double step) {
  return {Rounded(v[0], step), Rounded(v[1], step), Rounded(v[2], step)};
}

// A finite number of the record (named `name` in the error).
double FiniteNumber(const nlohmann::json& value, const std::string& name) {
  if (!value.is_number()) throw std::runtime_error("'" + name + "' is not a number");
  const double number = value.get<double>();
  if (!std::isfinite(number)) throw std::runtime_error("'" + name + "' is not finite");
  return number;
}

// Three numbers, each finite or null (an unknown standard deviation).
cv::Vec3d ThreeNumbers(const nlohmann::json& value, const std::string& name) {
  if (!value.is_array() || value.size() != 3) {
    throw std::runtime_error("'" + name + "' needs 3 numbers");
  }
  cv::Vec3d v;
  for (int k = 0; k < 3; ++k) {
    v[k] = value[k].is_null() ? std::numeric_limits<double>::quiet_NaN()
                              : FiniteNumber(value[k], name);
  }
  return v;
}

}  // namespace

std::string FrameRecordToJson(const FrameRecord& record) {
  nlohmann::ordered_json targets = nlohmann::ordered_json::array();
  for (const TargetRecord& t : record.targets) {
    nlohmann::ordered_json target = {{"id", t.id},
                                     {"bbox", {t.bbox.x, t.bbox.y, t.bbox.width, t.bbox.height}},
                                     {"area", t.area},
                                     {"saliency", t.saliency},
                                     {"state", TargetStateName(t.state)},
                                     {"kind", t.kind},
                                     {"similarity", t.similarity},
                                     {"tracker", t.tracker}};
    if (t.reason != ReleaseReason::kNone) target["reason"] = ReleaseReasonName(t.reason);
    if (t.state == TargetState::kResumed) target["absent_frames"] = t.absent_frames;
    if (!t.label.empty()) target["label"] = t.label;
    if (std::isfinite(t.disparity_px)) {
      target["disparity_px"] = Rounded(t.disparity_px, 1e-3);
      target["disparity_sd_px"] = Rounded(t.disparity_sd_px, 1e-3);
    }
    if (t.has_position) {
      target["position_m"] = Rounded3(t.position_m, 1e-4);
      target["position_sd_m"] = Rounded3(t.position_sd_m, 1e-4);
    }
    if (!t.depth_missing.empty()) target["depth_missing"] = t.depth_missing;
    targets.push_back(target);
  }
  nlohmann::ordered_json timings = nlohmann::ordered_json::object();
  for (const auto& [stage, ms] : record.timings.stages()) timings[stage] = ms;
  nlohmann::ordered_json line = {
      {"frame", record.frame}, {"targets", targets}, {"new", record.new_ids}};
  if (record.inhibited_fraction >= 0.0) line["inhibited_fraction"] = record.inhibited_fraction;
  line["timings_ms"] = timings;
  if (record.latency_ms >= 0.0) line["latency_ms"] = record.latency_ms;
  return JsonText(line);
}

namespace {

// `value` (named `name` in the error) as an integer in [min, max]; throws otherwise (the
// reader below adds the file and line).
int IntIn(const nlohmann::json& value, const std::string& name, long min, long max) {
  if (!value.is_number_integer()) throw std::runtime_error("'" + name + "' is not an integer");
  const auto number = value.get<int64_t>();
  // An unsigned value above INT64_MAX reads as negative, and is refused as out of range too.
  if (number < min || number > max || (value.is_number_unsigned() && number < 0)) {
    throw std::runtime_error("'" + name + "' out of range: " + value.dump() + " (must be in " +
                             std::to_string(min) + ".." + std::to_string(max) + ")");
  }
  return static_cast<int>(number);
}

// The fields of a stereo run's target (issue 44); absent in older records and mono runs.
void ReadDepth(const nlohmann::json& t, TargetRecord* target) {
  if (t.contains("disparity_px")) {
    target->disparity_px = FiniteNumber(t.at("disparity_px"), "disparity_px");
    if (t.contains("disparity_sd_px") && !t.at("disparity_sd_px").is_null()) {
      target->disparity_sd_px = FiniteNumber(t.at("disparity_sd_px"), "disparity_sd_px");
    }
  }
  if (t.contains("position_m")) {
    target->position_m = ThreeNumbers(t.at("position_m"), "position_m");
    if (!(std::isfinite(target->position_m[0]) && std::isfinite(target->position_m[1]) &&
          std::isfinite(target->position_m[2]))) {
      throw std::runtime_error("'position_m' needs 3 numbers");
    }
    target->has_position = true;
    if (t.contains("position_sd_m")) {
      target->position_sd_m = ThreeNumbers(t.at("position_sd_m"), "position_sd_m");
    }
  }
}

}  // namespace

namespace {

// One target of a record, but its depth (ReadDepth); std::runtime_error for a bad field.
TargetRecord ReadTarget(const nlohmann::json& t) {
  TargetRecord target;
  target.id = IntIn(t.at("id"), "id", 0, kMaxId);
  const nlohmann::json& box = t.at("bbox");
  if (!box.is_array() || box.size() != 4) throw std::runtime_error("bbox needs 4 numbers");
  // Bounded so that areas and corners cannot overflow int in the scorers.
  const int x = IntIn(box[0], "bbox x", -kMaxBoxCoordinate, kMaxBoxCoordinate);
  const int y = IntIn(box[1], "bbox y", -kMaxBoxCoordinate, kMaxBoxCoordinate);
  const int w = IntIn(box[2], "bbox w", 0, kMaxBoxCoordinate);
  const int h = IntIn(box[3], "bbox h", 0, kMaxBoxCoordinate);
  target.bbox = cv::Rect(x, y, w, h);
  target.area = IntIn(t.at("area"), "area", 0, 1L << 30);
  target.saliency = t.at("saliency").get<double>();
  const std::string state = t.at("state").get<std::string>();
  if (!TargetStateFromName(state, &target.state)) {
    throw std::runtime_error("unknown state '" + state + "'");
  }
  target.kind = t.at("kind").get<std::string>();
  target.similarity = t.at("similarity").get<std::string>();
  if (t.contains("absent_frames")) {
    target.absent_frames = IntIn(t.at("absent_frames"), "absent_frames", 0, kMaxFrameNumber);
  }
  if (t.contains("label")) target.label = t.at("label").get<std::string>();
  if (t.contains("depth_missing")) target.depth_missing = t.at("depth_missing").get<std::string>();
  return target;
}

// Reads the next line of `in` into `line` (without its '\n'); false at the end. A line longer
// than kMaxRecordBytes is an InputError naming it, before it is held whole.
bool ReadRecordLine(std::istream& in, const std::string& path, int number, std::string* line) {
  line->clear();
  std::streambuf* buffer = in.rdbuf();
  for (;;) {
    const int c = buffer->sbumpc();
    if (c == std::char_traits<char>::eof()) return !line->empty();
    if (c == '\n') return true;
    if (static_cast<long>(line->size()) >= kMaxRecordBytes) {
      throw InputError(path + ":" + std::to_string(number) + ": a record longer than " +
                       std::to_string(kMaxRecordBytes >> 20) + " MB (docs/LIMITS.md)");
    }
    line->push_back(static_cast<char>(c));
  }
}

// The record's targets into `record`, and their ids into `ids`. An id has at
// most one box a frame (a state that is seen: new, tracked, resumed) and at most one entry
// without: a target released or lost in a frame may be resumed from its object file under the
// same id in that frame, which records the id twice.
void ReadTargets(const nlohmann::json& targets, FrameRecord* record, std::set<int>* ids) {
  if (!targets.is_array()) throw std::runtime_error("'targets' is not a list");
  if (targets.size() > static_cast<size_t>(kMaxTargetsPerRecord)) {
    throw std::runtime_error(std::to_string(targets.size()) + " targets, more than " +
                             std::to_string(kMaxTargetsPerRecord) + " (docs/LIMITS.md)");
  }
  std::map<int, size_t> seen, unseen;  // id -> its position in the record, for duplicates
  for (const nlohmann::json& t : targets) {
    TargetRecord target = ReadTarget(t);
    ReadDepth(t, &target);
    std::map<int, size_t>& same = Visible(target.state) ? seen : unseen;
    const auto [at, first] = same.emplace(target.id, record->targets.size());
    if (!first) {
      throw std::runtime_error(
          "target id " + std::to_string(target.id) + " twice (targets " +
          std::to_string(at->second + 1) + " and " + std::to_string(record->targets.size() + 1) +
          "): a target is recorded once a frame, and once more only when it ended there and "
          "was resumed under its id");
    }
    record->targets.push_back(target);
    ids->insert(target.id);
  }
}

}  // namespace

std::vector<FrameRecord> ReadFrameRecords(const std::string& path) {
  std::error_code error;
  if (!std::filesystem::exists(path, error)) {
    throw InputError(path + ": cannot read (is this a run folder?)");
  }
  RequireRegularFile(path, "the frame records", ExitStatus::kBadInput);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot read (is this a run folder?)");
  std::vector<FrameRecord> frames;
  std::string line;
  int previous_line = 0;  // the line of the last record read
  for (int number = 1; ReadRecordLine(in, path, number, &line); ++number) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    try {
      const nlohmann::json json = nlohmann::json::parse(line);
      FrameRecord record;
      record.frame = IntIn(json.at("frame"), "frame", 0, kMaxFrameNumber);
      std::set<int> seen;  // the record's target ids
      ReadTargets(json.at("targets"), &record, &seen);
      record.new_ids = json.at("new").get<std::vector<int>>();
      for (const int id : record.new_ids) {
        // Each new id is one of the record's targets, which are unique and capped.
        if (seen.erase(id) == 0) {
          throw std::runtime_error("'new' has id " + std::to_string(id) +
                                   (std::count(record.new_ids.begin(), record.new_ids.end(), id) > 1
                                        ? " twice"
                                        : ", which is not a target of the record"));
        }
      }
      const nlohmann::json& timings = json.at("timings_ms");
      if (!timings.is_object()) {
        throw std::runtime_error("'timings_ms' is not a map of stage names to milliseconds");
      }
      for (const auto& [stage, ms] : timings.items()) {
        record.timings.Add(stage, ms.get<double>());
      }
      if (json.contains("latency_ms")) record.latency_ms = json.at("latency_ms").get<double>();
      // A run records each frame once, in increasing order; a second record of a frame would
      // be scored as if it were another frame.
      if (!frames.empty() && record.frame <= frames.back().frame) {
        const int before = frames.back().frame;
        throw InputError(
            path + ":" + std::to_string(number) + ": " +
            (record.frame == before
                ? "frame " + std::to_string(record.frame) + " again (line " +
                      std::to_string(previous_line) + " has it too)"
                : "frame " + std::to_string(record.frame) + " after frame " +
                      std::to_string(before) + " (line " + std::to_string(previous_line) +
                      "): the records must be in increasing frame order"));
      }
      previous_line = number;
      frames.push_back(std::move(record));
    } catch (const InputError&) {
      throw;
    } catch (const std::exception& e) {
      throw InputError(path + ":" + std::to_string(number) + ": not a frame record (" + e.what() +
                       ")");
    }
  }
  return frames;
}

}  // namespace attend
