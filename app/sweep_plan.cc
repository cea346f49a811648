#include "app/sweep_plan.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include <unistd.h>

#include "app/home.h"
#include "app/render_scene.h"
#include "app/run_attention.h"
#include "config/param_block.h"
#include "eval/fixation_data.h"
#include "io/tracking_files.h"
#include "pipeline/options_io.h"
#include "util/error.h"
#include "util/output_folder.h"
#include "util/strings.h"

namespace attend {

namespace {

namespace fs = std::filesystem;

const std::vector<std::string>& TopLevelKeys() {
  static const std::vector<std::string> keys = {"command", "config", "set",   "grid",
                                                "zip",     "inputs", "score", "slurm"};
  return keys;
}

const std::vector<std::string>& InputKeys() {
  static const std::vector<std::string> keys = {
      "name", "sequence", "video", "images", "left", "right", "side_by_side",
      "fixations", "scene", "gt", "frames", "skip", "first"};
  return keys;
}

// The source kinds an input may name (one of them), and `right` beside `left`.
const std::vector<std::string>& SourceKinds() {
  static const std::vector<std::string> kinds = {"sequence",     "video",     "images", "left",
                                                 "side_by_side", "fixations", "scene"};
  return kinds;
}

// Reading the sweep file's raw YAML with its lines, for the parts ParamBlock does not type
// (parameter values of any type, the inputs' paths).
class SweepReader {
 public:
  SweepReader(std::string file, std::string folder) : file_(std::move(file)), folder_(folder) {}

  std::string At(const YAML::Node& node) const {
    return file_ + ":" + std::to_string(node.Mark().line + 1);
  }
  [[noreturn]] void Fail(const YAML::Node& node, const std::string& key,
                         const std::string& message) const {
    throw ConfigError(At(node) + ": " + key + ": " + message);
  }
  // Every key of `map` must be one of `known`.
  void CheckKeys(const YAML::Node& map, const std::string& path,
                 const std::vector<std::string>& known) const {
    for (const auto& entry : map) {
      const std::string key = entry.first.as<std::string>();
      if (std::find(known.begin(), known.end(), key) == known.end()) {
        Fail(entry.first, path.empty() ? key : path + "." + key,
             "unknown key" + DidYouMean(key, known) + " (known: " + Join(known, ", ") + ")");
      }
    }
  }
  std::string String(const YAML::Node& node, const std::string& key) const {
    if (!node.IsScalar()) Fail(node, key, "expected a string");
    return node.as<std::string>();
  }
  int Int(const YAML::Node& node, const std::string& key, int low, int high) const {
    int value = 0;
    if (!node.IsScalar() || !YAML::convert<int>::decode(node, value)) {
      Fail(node, key, "expected an integer");
    }
    if (value < low || value > high) {
      Fail(node, key, "must be in [" + std::to_string(low) + ", " + std::to_string(high) + "]");
    }
    return value;
  }
  // A path relative to the sweep file's folder, made absolute.
  std::string Path(const YAML::Node& node, const std::string& key) const {
    const std::string text = String(node, key);
    if (text.empty()) Fail(node, key, "an empty path");
    fs::path path(text);
    if (path.is_relative()) path = fs::path(folder_) / path;
    return path.lexically_normal().string();
  }
  const std::string& file() const { return file_; }

 private:
  std::string file_;
  std::string folder_;
};

// `node` in YAML's flow style, the text a --set value takes.
std::string FlowText(const YAML::Node& node) {
  YAML::Emitter emitter;
  emitter << YAML::Flow << node;
  return emitter.c_str();
}

// Letters, digits and . _ = + - kept; any other run of bytes becomes one '-'.
std::string FileSafe(const std::string& text, std::size_t max_length) {
  std::string out;
  for (const char c : text) {
    const bool keep = std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '_' ||
                      c == '=' || c == '+' || c == '-';
    if (keep) {
      out += c;
    } else if (out.empty() || out.back() != '-') {
      out += '-';
    }
  }
  while (!out.empty() && (out.front() == '-' || out.front() == '.')) out.erase(out.begin());
  if (out.size() > max_length) out.resize(max_length);
  while (!out.empty() && out.back() == '-') out.pop_back();
  return out;
}

// The shortest dotted suffix of `key` that no other swept key ends with.
std::string ShortKey(const std::string& key, const std::vector<std::string>& keys) {
  const std::vector<std::string> parts = Split(key, '.');
  for (std::size_t take = 1; take <= parts.size(); ++take) {
    std::vector<std::string> tail(parts.end() - static_cast<long>(take), parts.end());
    const std::string suffix = Join(tail, ".");
    bool unique = true;
    for (const std::string& other : keys) {
      if (other == key) continue;
      if (other == suffix || (other.size() > suffix.size() &&
                              other.compare(other.size() - suffix.size(), suffix.size(),
                                            suffix) == 0 &&
                              other[other.size() - suffix.size() - 1] == '.')) {
        unique = false;
      }
    }
    if (unique) return suffix;
  }
  return key;
}

std::string CellName(const SweepInput& input, const std::vector<SweepSetting>& settings,
                     const std::vector<std::string>& keys) {
  std::string readable = input.name;
  std::string identity = input.name;
  for (const auto& [key, value] : settings) {
    readable += "_" + ShortKey(key, keys) + "=" + value;
    identity += "\n" + key + "=" + value;
  }
  char hash[9];
  std::snprintf(hash, sizeof(hash), "%08x", static_cast<unsigned>(Fnv1a(identity) & 0xffffffffU));
  return FileSafe(readable, 100) + "-" + hash;
}

// The parameters: the grid (every combination) and the zip groups (lists changed together).
struct SweptValues {
  std::string key;
  std::vector<std::string> values;
  std::vector<YAML::Node> nodes;  // where each value was written
};

// A grid's list may not hold a value twice (the cells would be the same); a zip group's lists
// may, as long as no two steps are the same.
std::vector<SweptValues> ReadValueLists(const SweepReader& reader, const YAML::Node& map,
                                        const std::string& section) {
  if (!map.IsMap()) reader.Fail(map, section, "expected a map of configuration keys to lists");
  if (map.size() == 0) {
    reader.Fail(map, section, "empty: give at least one key with a list of values");
  }
  std::vector<SweptValues> lists;
  for (const auto& entry : map) {
    SweptValues swept;
    swept.key = entry.first.as<std::string>();
    const std::string path = section + "." + swept.key;
    if (!entry.second.IsSequence()) {
      reader.Fail(entry.second, path, "expected a list of values (write [" +
                                          FlowText(entry.second) + "] for one value)");
    }
    if (entry.second.size() == 0) reader.Fail(entry.second, path, "an empty list of values");
    std::set<std::string> seen;
    for (const YAML::Node& value : entry.second) {
      const std::string text = FlowText(value);
      if (!seen.insert(text).second && section == "grid") {
        reader.Fail(value, path, "the value " + text + " twice");
      }
      swept.values.push_back(text);
      swept.nodes.push_back(value);
    }
    lists.push_back(std::move(swept));
  }
  return lists;
}

// Options of the configuration with these overrides; a ConfigError is the configuration's.
void CheckConfiguration(SweepCommand command, const std::string& config,
                        const std::vector<std::string>& sets) {
  if (command == SweepCommand::kTrack) {
    ParamBlock root = ParamBlock::Parse("", "--set");
    for (const std::string& set : sets) root.Override(set);
    ReadOptions(root);
  } else {
    LoadOptions(config, sets);
  }
}

// The folder a scene renders into: DIR/scenes/<stem>-<FNV-1a of the scene file's text>, so a
// changed scene renders anew.
std::string SceneFolder(const std::string& scene, const std::string& dir) {
  char hash[17];
  std::snprintf(hash, sizeof(hash), "%016llx",
                static_cast<unsigned long long>(Fnv1a(ReadFileText(scene))));
  return (fs::path(dir.empty() ? "SWEEP_DIR" : dir) / "scenes" /
          (fs::path(scene).stem().string() + "-" + hash))
      .lexically_normal()
      .string();
}

SweepInput ReadInput(const SweepReader& reader, const YAML::Node& node, std::size_t index,
                     SweepCommand command, const std::string& dir) {
  const std::string path = "inputs[" + std::to_string(index) + "]";
  if (!node.IsMap()) reader.Fail(node, path, "expected a map such as {sequence: FOLDER}");
  reader.CheckKeys(node, path, InputKeys());
  SweepInput input;
  input.where = reader.At(node);
  std::vector<std::string> kinds;
  for (const std::string& kind : SourceKinds()) {
    if (node[kind]) kinds.push_back(kind);
  }
  if (kinds.size() != 1) {
    reader.Fail(node, path,
                kinds.empty() ? "names no source: give one of " + Join(SourceKinds(), ", ")
                              : "names " + Join(kinds, " and ") + ": give one source an input");
  }
  input.kind = kinds[0];
  const YAML::Node source = node[input.kind];
  const std::string key = path + "." + input.kind;
  input.path = reader.Path(source, key);
  const bool folder = input.kind == "sequence" || input.kind == "images" ||
                      input.kind == "fixations";
  std::error_code error;
  if (folder ? !fs::is_directory(input.path, error) : !fs::is_regular_file(input.path, error)) {
    reader.Fail(source, key, input.path + ": no such " + (folder ? "folder" : "file"));
  }
  if (input.kind == "scene") {
    if (command != SweepCommand::kRun) reader.Fail(source, key, "scenes are for command run");
    input.scene = input.path;
    input.path = SceneFolder(input.scene, dir);
  }
  if (node["right"]) {
    if (input.kind != "left") reader.Fail(node["right"], path + ".right", "only beside left");
    input.right = reader.Path(node["right"], path + ".right");
    if (!fs::is_regular_file(input.right, error)) {
      reader.Fail(node["right"], path + ".right", input.right + ": no such file");
    }
  } else if (input.kind == "left") {
    reader.Fail(node, path, "left needs right (a left/right pair of videos)");
  }
  if (node["frames"]) input.frames = reader.String(node["frames"], path + ".frames");
  if (node["skip"] || node["first"]) {
    if (input.kind != "fixations") {
      reader.Fail(node["skip"] ? node["skip"] : node["first"], path,
                  "skip and first are for fixation datasets");
    }
    if (node["skip"]) input.skip = reader.Int(node["skip"], path + ".skip", 0, 1000000);
    if (node["first"]) input.first = reader.Int(node["first"], path + ".first", 0, 1000000);
  }
  if (node["gt"]) input.gt = reader.Path(node["gt"], path + ".gt");

  // What each command takes, and its ground truth.
  const std::string command_name = SweepCommandName(command);
  if (command == SweepCommand::kSaliency) {
    if (input.kind != "fixations") {
      reader.Fail(source, key, "command saliency takes fixation datasets (fixations: FOLDER)");
    }
    if (!input.gt.empty()) reader.Fail(node["gt"], path + ".gt", "a fixation dataset is its gt");
  } else if (input.kind == "fixations") {
    reader.Fail(source, key, "a fixation dataset needs command: saliency");
  }
  if (command == SweepCommand::kTrack) {
    if (input.kind != "images" && input.kind != "sequence") {
      reader.Fail(source, key, "command track takes images or sequence folders");
    }
    if (input.gt.empty()) {
      reader.Fail(node, path, "command track needs gt: an OTB groundtruth_rect.txt");
    }
    if (!fs::is_regular_file(input.gt, error)) {
      reader.Fail(node["gt"], path + ".gt", input.gt + ": no such file");
    }
  }
  // attend eval's ground truth: the input's gt:, else a sequence's own gt/ (a rendered scene
  // brings its own).
  if (command == SweepCommand::kRun && !(input.kind == "scene" && input.gt.empty())) {
    const std::string gt =
        !input.gt.empty() ? input.gt
                          : (input.kind == "sequence" ? (fs::path(input.path) / "gt").string() : "");
    if (gt.empty()) {
      reader.Fail(node, path,
                  "attend eval needs ground truth: give gt: (a folder holding objects.csv)");
    }
    if (!fs::is_regular_file(fs::path(gt) / "objects.csv", error)) {
      reader.Fail(node["gt"] ? node["gt"] : source, node["gt"] ? path + ".gt" : key,
                  gt + ": no objects.csv (the ground truth attend eval scores against)");
    }
  }

  if (node["name"]) {
    input.name = reader.String(node["name"], path + ".name");
  } else {
    fs::path named(input.kind == "scene" ? input.scene : input.path);
    // An OTB sequence's frames are in NAME/img.
    if (named.filename() == "img" && named.has_parent_path()) named = named.parent_path();
    input.name = named.filename().string();
    if (input.kind == "video" || input.kind == "left" || input.kind == "side_by_side" ||
        input.kind == "scene") {
      input.name = named.stem().string();
    }
  }
  input.name = FileSafe(input.name, 40);
  if (input.name.empty()) reader.Fail(node, path + ".name", "no usable name: give name:");
  return input;
}

}  // namespace

const char* SweepCommandName(SweepCommand command) {
  switch (command) {
    case SweepCommand::kRun:
      return "run";
    case SweepCommand::kTrack:
      return "track";
    case SweepCommand::kSaliency:
      return "saliency";
  }
  return "run";
}

SweepPlan ReadSweepFile(const std::string& path, const SweepReadOptions& options) {
  SweepPlan plan;
  plan.file = fs::absolute(path).lexically_normal().string();
  std::error_code error;
  if (options.text == nullptr && !fs::is_regular_file(path, error)) {
    throw ConfigError(path + ": no such sweep file");
  }
  plan.text = options.text != nullptr ? *options.text : ReadFileText(path);
  const std::string dir =
      options.dir.empty() ? "" : fs::absolute(options.dir).lexically_normal().string();
  // ParamBlock checks the text (UTF-8, syntax, duplicate keys, a map at the top) and types the
  // plain sections; the raw tree gives the parameter values and their lines.
  const ParamBlock block = ParamBlock::Parse(plan.text, plan.file);
  const YAML::Node root = YAML::Load(plan.text);
  const SweepReader reader(plan.file, fs::path(plan.file).parent_path().string());
  if (!root.IsDefined() || root.IsNull()) throw ConfigError(plan.file + ": an empty sweep file");
  reader.CheckKeys(root, "", TopLevelKeys());

  // The command, from the file or from the inputs.
  std::string command = block.GetString("command", "");
  if (command.empty()) {
    bool fixations = false;
    if (root["inputs"] && root["inputs"].IsSequence()) {
      for (const YAML::Node& input : root["inputs"]) fixations = fixations || input["fixations"];
    }
    command = fixations ? "saliency" : "run";
  }
  if (command == "run") {
    plan.command = SweepCommand::kRun;
  } else if (command == "track") {
    plan.command = SweepCommand::kTrack;
  } else if (command == "saliency") {
    plan.command = SweepCommand::kSaliency;
  } else {
    reader.Fail(root["command"], "command",
                "'" + command + "' is not one of run, track, saliency" +
                    DidYouMean(command, {"run", "track", "saliency"}));
  }

  if (plan.command == SweepCommand::kTrack) {
    if (root["config"]) {
      reader.Fail(root["config"], "config",
                  "command track takes no configuration file, only tracker.* keys");
    }
  } else {
    plan.config = root["config"] ? reader.Path(root["config"], "config") : DefaultConfigPath();
    std::error_code error;
    if (!fs::is_regular_file(plan.config, error)) {
      if (root["config"]) reader.Fail(root["config"], "config", plan.config + ": no such file");
      throw ConfigError(plan.config + ": the default configuration is missing");
    }
  }

  // Keys of the configuration: those of the sets, the grid and the zips, each once.
  std::map<std::string, std::string> key_where;
  const auto claim = [&](const YAML::Node& node, const std::string& key,
                         const std::string& section) {
    const auto [it, inserted] = key_where.emplace(key, reader.At(node));
    if (!inserted) {
      reader.Fail(node, section + "." + key, "also given at " + it->second + "; give a key once");
    }
    if (plan.command == SweepCommand::kTrack && key.rfind("tracker.", 0) != 0) {
      reader.Fail(node, section + "." + key, "command track takes only tracker.* keys");
    }
  };
  if (root["set"] && !root["set"].IsNull()) {
    if (!root["set"].IsMap()) reader.Fail(root["set"], "set", "expected a map of keys to values");
    for (const auto& entry : root["set"]) {
      const std::string key = entry.first.as<std::string>();
      claim(entry.first, key, "set");
      plan.sets.push_back(key + "=" + FlowText(entry.second));
    }
  }
  std::vector<SweptValues> grid;
  if (root["grid"]) {
    grid = ReadValueLists(reader, root["grid"], "grid");
    for (const SweptValues& swept : grid) claim(swept.nodes[0], swept.key, "grid");
  }
  std::vector<std::vector<SweptValues>> zips;
  if (root["zip"]) {
    std::vector<YAML::Node> groups;
    if (root["zip"].IsSequence()) {
      for (const YAML::Node& group : root["zip"]) groups.push_back(group);
      if (groups.empty()) reader.Fail(root["zip"], "zip", "an empty list of zip groups");
    } else {
      groups.push_back(root["zip"]);
    }
    for (const YAML::Node& group : groups) {
      zips.push_back(ReadValueLists(reader, group, "zip"));
      const std::vector<SweptValues>& lists = zips.back();
      std::set<std::vector<std::string>> steps;
      for (std::size_t step = 0; step < lists[0].values.size(); ++step) {
        std::vector<std::string> values;
        for (const SweptValues& swept : lists) {
          values.push_back(step < swept.values.size() ? swept.values[step] : "");
        }
        if (!steps.insert(values).second) {
          reader.Fail(lists[0].nodes[step], "zip." + lists[0].key,
                      "step " + std::to_string(step + 1) + " repeats an earlier step of the group");
        }
      }
      for (const SweptValues& swept : lists) {
        claim(swept.nodes[0], swept.key, "zip");
        if (swept.values.size() != lists[0].values.size()) {
          reader.Fail(swept.nodes[0], "zip." + swept.key,
                      std::to_string(swept.values.size()) + " values beside " +
                          std::to_string(lists[0].values.size()) + " of zip." + lists[0].key +
                          ": lists zipped together have the same length");
        }
      }
    }
  }
  for (const SweptValues& swept : grid) {
    plan.groups.push_back({static_cast<int>(plan.keys.size())});
    plan.keys.push_back(swept.key);
  }
  for (const auto& group : zips) {
    plan.groups.emplace_back();
    for (const SweptValues& swept : group) {
      plan.groups.back().push_back(static_cast<int>(plan.keys.size()));
      plan.keys.push_back(swept.key);
    }
  }

  // Every value on its own over the base, so an error names its line; then the fixed sets.
  try {
    CheckConfiguration(plan.command, plan.config, plan.sets);
  } catch (const ConfigError& e) {
    reader.Fail(root["set"], "set", e.what());
  }
  const auto check_values = [&](const std::vector<SweptValues>& lists, const std::string& section) {
    for (const SweptValues& swept : lists) {
      for (std::size_t v = 0; v < swept.values.size(); ++v) {
        std::vector<std::string> sets = plan.sets;
        sets.push_back(swept.key + "=" + swept.values[v]);
        try {
          CheckConfiguration(plan.command, plan.config, sets);
        } catch (const ConfigError& e) {
          reader.Fail(swept.nodes[v], section + "." + swept.key, e.what());
        }
      }
    }
  };
  check_values(grid, "grid");
  for (const auto& group : zips) check_values(group, "zip");

  // The configurations: the grid's combinations (last key fastest) times each zip group's steps.
  std::vector<std::vector<SweepSetting>> configurations = {{}};
  const auto cross = [&](const std::vector<std::vector<SweepSetting>>& choices) {
    std::vector<std::vector<SweepSetting>> next;
    for (const auto& partial : configurations) {
      for (const auto& choice : choices) {
        std::vector<SweepSetting> combined = partial;
        combined.insert(combined.end(), choice.begin(), choice.end());
        next.push_back(std::move(combined));
      }
    }
    configurations = std::move(next);
  };
  for (const SweptValues& swept : grid) {
    std::vector<std::vector<SweepSetting>> choices;
    for (const std::string& value : swept.values) choices.push_back({{swept.key, value}});
    cross(choices);
  }
  for (const auto& group : zips) {
    std::vector<std::vector<SweepSetting>> choices;
    for (std::size_t step = 0; step < group[0].values.size(); ++step) {
      std::vector<SweepSetting> choice;
      for (const SweptValues& swept : group) choice.push_back({swept.key, swept.values[step]});
      choices.push_back(std::move(choice));
    }
    cross(choices);
  }
  // Combinations too: a value can be valid alone and not beside another (a check across keys).
  for (const auto& settings : configurations) {
    std::vector<std::string> sets = plan.sets;
    std::vector<std::string> named;
    for (const auto& [key, value] : settings) {
      sets.push_back(key + "=" + value);
      named.push_back(key + "=" + value);
    }
    try {
      CheckConfiguration(plan.command, plan.config, sets);
    } catch (const ConfigError& e) {
      throw ConfigError(plan.file + ": the cell " + Join(named, ", ") + ": " + e.what());
    }
  }

  // The inputs.
  const YAML::Node inputs = root["inputs"];
  if (!inputs || inputs.IsNull()) {
    throw ConfigError(plan.file + ": inputs: missing: give the sequences, videos, image folders "
                      "or fixation datasets to run on");
  }
  if (!inputs.IsSequence() || inputs.size() == 0) {
    reader.Fail(inputs, "inputs", "expected a non-empty list of inputs");
  }
  std::set<std::string> names;
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    plan.inputs.push_back(ReadInput(reader, inputs[i], i, plan.command, dir));
    if (!names.insert(plan.inputs.back().name).second) {
      reader.Fail(inputs[i], "inputs[" + std::to_string(i) + "]",
                  "a second input named '" + plan.inputs.back().name + "': give each a name:");
    }
  }

  // Scoring: the scorer of the command, with its options.
  const ParamBlock score = block.Child("score");
  const std::string scorer = plan.command == SweepCommand::kRun     ? "eval"
                             : plan.command == SweepCommand::kTrack ? "eval-tracking"
                                                                    : "eval-fixations";
  for (const std::string& key : score.Keys()) {
    if (key != scorer) {
      score.Fail(key, "command " + std::string(SweepCommandName(plan.command)) + " is scored by " +
                          scorer + ", not " + key);
    }
  }
  if (plan.command == SweepCommand::kSaliency) {
    const ParamBlock options = score.Child(scorer);
    plan.fixations.sigma = options.GetDouble("sigma", plan.fixations.sigma, Range::Closed(0, 1e4));
    plan.fixations.max_side =
        options.GetInt("max_side", plan.fixations.max_side, Range::Closed(0, 100000));
    plan.fixations.baselines = options.GetStrings("baselines", {});
    for (const std::string& baseline : plan.fixations.baselines) {
      if (baseline != "centre" && baseline != "spectral_residual" && baseline != "fine_grained") {
        options.Fail("baselines", "'" + baseline +
                                      "' is not one of centre, spectral_residual, fine_grained");
      }
    }
    plan.fixations.baseline_blur =
        options.GetDouble("baseline_blur", plan.fixations.baseline_blur, Range::Closed(0, 1));
    options.CheckNoUnknownKeys();
  } else if (score.Has(scorer)) {
    score.Child(scorer).CheckNoUnknownKeys();
  }

  const ParamBlock slurm = block.Child("slurm");
  plan.slurm.partition = slurm.GetString("partition", "");
  plan.slurm.time = slurm.GetString("time", "");
  plan.slurm.mem = slurm.GetString("mem", "");
  plan.slurm.cpus_per_task = slurm.GetInt("cpus_per_task", 1, Range::Closed(1, 1024));
  plan.slurm.throttle = slurm.GetInt("throttle", 0, Range::Closed(0, 100000));
  slurm.CheckNoUnknownKeys();

  // The scenes, rendered once everything is checked: beside the target and renamed into place.
  if (options.render) {
    for (const SweepInput& input : plan.inputs) {
      std::error_code error;
      if (input.kind != "scene" || fs::exists(fs::path(input.path) / "sequence.yaml", error)) {
        continue;
      }
      fs::create_directories(fs::path(input.path).parent_path(), error);
      const std::string temporary = input.path + ".tmp-" + std::to_string(getpid());
      fs::remove_all(temporary, error);
      RenderSceneRequest request;
      request.scene = input.scene;
      request.out = temporary;
      RenderScene(request);
      fs::rename(temporary, input.path, error);
      fs::remove_all(temporary, error);
      if (!fs::exists(fs::path(input.path) / "sequence.yaml", error)) {
        throw OutputError(input.path + ": cannot write the rendered scene " + input.scene);
      }
    }
  }

  // The cells: configurations outermost, then the inputs.
  for (const auto& settings : configurations) {
    for (std::size_t i = 0; i < plan.inputs.size(); ++i) {
      SweepCell cell;
      cell.index = static_cast<int>(plan.cells.size());
      cell.input = static_cast<int>(i);
      cell.settings = settings;
      cell.name = CellName(plan.inputs[i], settings, plan.keys);
      plan.cells.push_back(std::move(cell));
    }
  }
  return plan;
}

std::vector<std::string> CellSets(const SweepPlan& plan, const SweepCell& cell) {
  std::vector<std::string> sets = plan.sets;
  for (const auto& [key, value] : cell.settings) sets.push_back(key + "=" + value);
  return sets;
}

std::string CellConfigYaml(const SweepPlan& plan, const SweepCell& cell) {
  if (plan.command == SweepCommand::kTrack) {
    ParamBlock root = ParamBlock::Parse("", "--set");
    for (const std::string& set : CellSets(plan, cell)) root.Override(set);
    return OptionsToYaml(ReadOptions(root));
  }
  return OptionsToYaml(LoadOptions(plan.config, CellSets(plan, cell)));
}

namespace {

// The source (io/source_spec.h) of an input of command run; a scene runs on the sequence it
// renders into.
SourceSpec RunInputSource(const SweepInput& input) {
  SourceSpec source;
  if (input.kind == "sequence" || input.kind == "scene") source.folder = input.path;
  if (input.kind == "left") source.left_video = input.path;
  source.right_video = input.right;
  if (input.kind == "side_by_side") source.side_by_side_video = input.path;
  if (input.kind == "video") source.video = input.path;
  if (input.kind == "images") source.images = input.path;
  return source;
}

}  // namespace

std::vector<std::vector<std::string>> CellCommands(const SweepPlan& plan, const SweepCell& cell,
                                                   const std::string& cell_dir) {
  const SweepInput& input = plan.inputs[cell.input];
  const std::string out = (fs::path(cell_dir) / "out").string();
  std::vector<std::string> sets;
  for (const std::string& set : CellSets(plan, cell)) {
    sets.push_back("--set");
    sets.push_back(set);
  }
  std::vector<std::string> compute;
  std::vector<std::string> score;
  switch (plan.command) {
    case SweepCommand::kRun: {
      compute = {"run", "--config", plan.config};
      compute.insert(compute.end(), sets.begin(), sets.end());
      const std::vector<std::string> source = RunSourceArguments(RunInputSource(input));
      compute.insert(compute.end(), source.begin(), source.end());
      if (!input.frames.empty()) compute.insert(compute.end(), {"--frames", input.frames});
      compute.insert(compute.end(), {"--out", out, "--overwrite", "--quiet"});
      score = {"eval", out};
      if (!input.gt.empty()) score.insert(score.end(), {"--gt", input.gt});
      break;
    }
    case SweepCommand::kTrack: {
      const std::vector<cv::Rect2d> truth = ReadOtbGroundTruth(input.gt);
      const int first = input.frames.empty() ? 0 : std::max(0, std::atoi(input.frames.c_str()));
      if (first >= static_cast<int>(truth.size()) || truth[first].area() <= 0) {
        throw InputError(input.gt + ": no box for frame " + std::to_string(first) +
                         " to start the tracker on");
      }
      const cv::Rect2d& box = truth[first];
      const std::string init = std::to_string(static_cast<int>(std::lround(box.x))) + "," +
                               std::to_string(static_cast<int>(std::lround(box.y))) + "," +
                               std::to_string(static_cast<int>(std::lround(box.width))) + "," +
                               std::to_string(static_cast<int>(std::lround(box.height)));
      compute = {"track", "--" + input.kind, input.path, "--init", init};
      compute.insert(compute.end(), sets.begin(), sets.end());
      if (!input.frames.empty()) compute.insert(compute.end(), {"--frames", input.frames});
      compute.insert(compute.end(), {"--out", out, "--overwrite"});
      score = {"eval-tracking", (fs::path(out) / "tracks.csv").string(), "--gt", input.gt,
               "--id", "1"};
      if (!input.frames.empty()) score.insert(score.end(), {"--frames", input.frames});
      break;
    }
    case SweepCommand::kSaliency: {
      const FixationDataset dataset = OpenFixationDataset(input.path);
      std::vector<FixationItem> items = dataset.items;
      items.erase(items.begin(), items.begin() + std::min<std::size_t>(input.skip, items.size()));
      if (input.first > 0 && static_cast<int>(items.size()) > input.first) {
        items.resize(input.first);
      }
      if (items.empty()) throw InputError(input.path + ": no images left after skip and first");
      const std::string maps = (fs::path(out) / "maps").string();
      compute = {"saliency"};
      for (const FixationItem& item : items) compute.push_back(item.stimulus_path);
      compute.insert(compute.end(), {"--config", plan.config});
      compute.insert(compute.end(), sets.begin(), sets.end());
      compute.insert(compute.end(), {"--out", maps, "--quiet"});
      score = {"eval-fixations", "attend=" + maps, "--dataset", input.path,
               "--skip", std::to_string(input.skip), "--first", std::to_string(input.first),
               "--sigma", ShortestNumber(plan.fixations.sigma), "--max-side",
               std::to_string(plan.fixations.max_side), "--baseline-blur",
               ShortestNumber(plan.fixations.baseline_blur)};
      if (!plan.fixations.baselines.empty()) {
        score.push_back("--baselines");
        score.insert(score.end(), plan.fixations.baselines.begin(), plan.fixations.baselines.end());
      }
      score.insert(score.end(), {"--out", (fs::path(out) / "scores").string(), "--quiet"});
      break;
    }
  }
  return {compute, score};
}

}  // namespace attend
