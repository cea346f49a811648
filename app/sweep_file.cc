// Step 1 of planning a sweep (app/sweep_plan.h): the sweep file's sections read and checked on
// their own; the inputs are in app/sweep_inputs.cc.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>
#include <set>

#include "app/home.h"
#include "app/sweep_inputs.h"
#include "app/sweep_plan.h"
#include "config/read_fields.h"
#include "config/yaml_document.h"
#include "eval/saliency_baselines.h"
#include "util/error.h"
#include "util/file_checks.h"
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

// The command, from the file or, when it names none, from the inputs (fixation datasets are
// scored by saliency).
SweepCommand ReadCommand(const YamlDocument& document) {
  const YAML::Node& root = document.root();
  const YAML::Node& given = root["command"];
  std::string command = given.IsDefined() ? document.String(given, "command") : "";
  if (command.empty()) {
    bool fixations = false;
    if (root["inputs"] && root["inputs"].IsSequence()) {
      for (const YAML::Node& input : root["inputs"]) fixations = fixations || input["fixations"];
    }
    command = fixations ? "saliency" : "run";
  }
  if (command == "run") return SweepCommand::kRun;
  if (command == "track") return SweepCommand::kTrack;
  if (command == "saliency") return SweepCommand::kSaliency;
  document.Fail(root["command"], "command",
                "'" + command + "' is not one of run, track, saliency" +
                    DidYouMean(command, {"run", "track", "saliency"}));
}

// The base configuration file: `config:`, else the default one; none for track.
std::string ReadBaseConfig(const YamlDocument& document, SweepCommand command) {
  const YAML::Node& root = document.root();
  if (command == SweepCommand::kTrack) {
    if (root["config"]) {
      document.Fail(root["config"], "config",
                    "command track takes no configuration file, only tracker.* keys");
    }
    return "";
  }
  const std::string config =
      root["config"] ? document.Path(root["config"], "config") : DefaultConfigPath();
  std::error_code error;
  if (!fs::is_regular_file(config, error)) {
    if (root["config"]) document.Fail(root["config"], "config", config + ": no such file");
    throw ConfigError(config + ": the default configuration is missing");
  }
  return config;
}

// The configuration keys of set, grid and zip: each given once; command track takes only
// tracker.* keys.
class KeyClaims {
 public:
  explicit KeyClaims(SweepCommand command) : command_(command) {}

  void Claim(const std::string& where, const std::string& key, const std::string& section) {
    const auto [it, inserted] = where_.emplace(key, where);
    if (!inserted) {
      throw ConfigError(where + ": " + section + "." + key + ": also given at " + it->second +
                        "; give a key once");
    }
    if (command_ == SweepCommand::kTrack && key.rfind("tracker.", 0) != 0) {
      throw ConfigError(where + ": " + section + "." + key +
                        ": command track takes only tracker.* keys");
    }
  }

 private:
  SweepCommand command_;
  std::map<std::string, std::string> where_;
};

// The lists of a grid or a zip group. A grid's list may not hold a value twice (the cells would
// be the same); a zip group's lists may, as long as no two steps are the same.
std::vector<SweptList> ReadValueLists(const YamlDocument& document, const YAML::Node& map,
                                      const std::string& section) {
  if (!map.IsMap()) document.Fail(map, section, "expected a map of configuration keys to lists");
  if (map.size() == 0) {
    document.Fail(map, section, "empty: give at least one key with a list of values");
  }
  std::vector<SweptList> lists;
  for (const auto& entry : map) {
    SweptList swept;
    swept.key = entry.first.as<std::string>();
    const std::string path = section + "." + swept.key;
    if (!entry.second.IsSequence()) {
      document.Fail(
          entry.second, path,
          "expected a list of values (write [" + FlowText(entry.second) + "] for one value)");
    }
    if (entry.second.size() == 0) document.Fail(entry.second, path, "an empty list of values");
    std::set<std::string> seen;
    for (const YAML::Node& value : entry.second) {
      const std::string text = FlowText(value);
      if (!seen.insert(text).second && section == "grid") {
        document.Fail(value, path, "the value " + text + " twice");
      }
      swept.values.push_back(text);
      swept.where.push_back(document.At(value));
    }
    lists.push_back(std::move(swept));
  }
  return lists;
}

// A zip group's lists: no step twice, every list as long as the first.
std::vector<SweptList> ReadZipGroup(const YamlDocument& document, const YAML::Node& group,
                                    KeyClaims* claims) {
  std::vector<SweptList> lists = ReadValueLists(document, group, "zip");
  std::set<std::vector<std::string>> steps;
  for (std::size_t step = 0; step < lists[0].values.size(); ++step) {
    std::vector<std::string> values;
    for (const SweptList& swept : lists) {
      values.push_back(step < swept.values.size() ? swept.values[step] : "");
    }
    if (!steps.insert(values).second) {
      throw ConfigError(lists[0].where[step] + ": zip." + lists[0].key + ": step " +
                        std::to_string(step + 1) + " repeats an earlier step of the group");
    }
  }
  for (const SweptList& swept : lists) {
    claims->Claim(swept.where[0], swept.key, "zip");
    if (swept.values.size() != lists[0].values.size()) {
      throw ConfigError(swept.where[0] + ": zip." + swept.key + ": " +
                        std::to_string(swept.values.size()) + " values beside " +
                        std::to_string(lists[0].values.size()) + " of zip." + lists[0].key +
                        ": lists zipped together have the same length");
    }
  }
  return lists;
}

// `set:`, `grid:` and `zip:` (a group, or a list of groups), and the swept keys they give.
void ReadSettings(const YamlDocument& document, SweepPlan* plan) {
  const YAML::Node& root = document.root();
  KeyClaims claims(plan->command);
  if (root["set"]) plan->sets_where = document.At(root["set"]);
  if (root["set"] && !root["set"].IsNull()) {
    if (!root["set"].IsMap()) document.Fail(root["set"], "set", "expected a map of keys to values");
    for (const auto& entry : root["set"]) {
      const std::string key = entry.first.as<std::string>();
      claims.Claim(document.At(entry.first), key, "set");
      plan->sets.push_back(key + "=" + FlowText(entry.second));
    }
  }
  if (root["grid"]) {
    plan->grid = ReadValueLists(document, root["grid"], "grid");
    for (const SweptList& swept : plan->grid) claims.Claim(swept.where[0], swept.key, "grid");
  }
  if (root["zip"]) {
    std::vector<YAML::Node> groups;
    if (root["zip"].IsSequence()) {
      for (const YAML::Node& group : root["zip"]) groups.push_back(group);
      if (groups.empty()) document.Fail(root["zip"], "zip", "an empty list of zip groups");
    } else {
      groups.push_back(root["zip"]);
    }
    for (const YAML::Node& group : groups) {
      plan->zips.push_back(ReadZipGroup(document, group, &claims));
    }
  }
  for (const SweptList& swept : plan->grid) {
    plan->groups.push_back({static_cast<int>(plan->keys.size())});
    plan->keys.push_back(swept.key);
  }
  for (const auto& group : plan->zips) {
    plan->groups.emplace_back();
    for (const SweptList& swept : group) {
      plan->groups.back().push_back(static_cast<int>(plan->keys.size()));
      plan->keys.push_back(swept.key);
    }
  }
}

// `score:`: the command's scorer only, with its options (eval-fixations has some).
FixationScoring ReadScoring(const ParamBlock& block, SweepCommand command) {
  const ParamBlock score = block.Child("score");
  const std::string scorer = command == SweepCommand::kRun     ? "eval"
                             : command == SweepCommand::kTrack ? "eval-tracking"
                                                               : "eval-fixations";
  for (const std::string& key : score.Keys()) {
    if (key != scorer) {
      score.Fail(key, "command " + std::string(SweepCommandName(command)) + " is scored by " +
                          scorer + ", not " + key);
    }
  }
  FixationScoring fixations;
  if (command == SweepCommand::kSaliency) {
    const ParamBlock options = score.Child(scorer);
    ReadFields(options, FixationScoring::Fields(), &fixations);
    options.CheckNoUnknownKeys();
  } else if (score.Has(scorer)) {
    score.Child(scorer).CheckNoUnknownKeys();
  }
  return fixations;
}

// The cells the file makes, counted before any is planned: a grid of 10^6 cells planned for
// minutes before. The product is taken in floating point (a grid of 20 lists of 100 values
// overflows any integer) and refused past kMaxSweepCells, naming each list's length.
void CheckCellCount(const YamlDocument& document, const SweepPlan& plan) {
  const YAML::Node& inputs = document.root()["inputs"];
  const std::size_t input_count = inputs && inputs.IsSequence() ? inputs.size() : 1;
  double cells = static_cast<double>(std::max<std::size_t>(1, input_count));
  std::vector<std::string> factors;
  for (const SweptList& swept : plan.grid) {
    cells *= static_cast<double>(swept.values.size());
    factors.push_back("grid." + swept.key + ": " + std::to_string(swept.values.size()));
  }
  for (const auto& group : plan.zips) {
    cells *= static_cast<double>(group[0].values.size());
    factors.push_back("zip." + group[0].key + " (and the lists zipped with it): " +
                      std::to_string(group[0].values.size()));
  }
  factors.push_back("inputs: " + std::to_string(input_count));
  if (cells <= static_cast<double>(kMaxSweepCells)) return;
  char count[32];
  std::snprintf(count, sizeof(count), cells < 1e15 ? "%.0f" : "%.3g", cells);
  const std::string where = !plan.grid.empty()  ? plan.grid[0].where[0]
                            : !plan.zips.empty() ? plan.zips[0][0].where[0]
                                                 : plan.file;
  throw ConfigError(where + ": the sweep has " + count + " cells (" + Join(factors, " x ") +
                    "), more than the " + std::to_string(kMaxSweepCells) +
                    " a sweep may have (docs/LIMITS.md): split it into several sweeps, or "
                    "sweep fewer values at once");
}

}  // namespace

const OptionFields<SlurmSettings>& SlurmSettings::Fields() {
  static const OptionFields<SlurmSettings> fields = {
      {"partition", &SlurmSettings::partition, "Slurm partition; \"\" the cluster's default"},
      {"time", &SlurmSettings::time,
       "time limit of a cell, as sbatch --time; \"\" the partition's default"},
      {"mem", &SlurmSettings::mem, "memory of a cell, as sbatch --mem; \"\" the default"},
      {"cpus_per_task", &SlurmSettings::cpus_per_task, Range::Closed(1, 1024), "CPUs of a cell"},
      {"throttle", &SlurmSettings::throttle, Range::Closed(0, 100000),
       "at most this many array tasks at once (%M); 0 no limit"}};
  return fields;
}

const OptionFields<FixationScoring>& FixationScoring::Fields() {
  static const OptionFields<FixationScoring> fields = {
      {"sigma", &FixationScoring::sigma, Range::Closed(0, 1e4),
       "fixation-density sigma in px at the scored size; 0: 0.025 x the larger side"},
      {"max_side", &FixationScoring::max_side, Range::Closed(0, 100000),
       "score at most this many px on the larger side; 0: the stimulus's size"},
      {"baselines", &FixationScoring::baselines, "baselines scored beside attend's maps",
       BaselineNames},
      {"baseline_blur", &FixationScoring::baseline_blur, Range::Closed(0, 1),
       "Gaussian blur of the OpenCV baselines, share of the larger side"}};
  return fields;
}

SweepPlan ReadSweepFile(const std::string& path, const SweepReadOptions& options) {
  SweepPlan plan;
  plan.file = fs::absolute(path).lexically_normal().string();
  // A folder, a fifo or /dev/zero is named as what it is; a sweep file is configuration-sized.
  plan.text = options.text != nullptr
                  ? *options.text
                  : ReadRegularFile(path, "the sweep file", ExitStatus::kUsage, kMaxConfigBytes);
  const std::string dir =
      options.dir.empty() ? "" : fs::absolute(options.dir).lexically_normal().string();
  const YamlDocument document(plan.text, plan.file);
  const YAML::Node& root = document.root();
  if (!root.IsDefined() || root.IsNull()) throw ConfigError(plan.file + ": an empty sweep file");
  document.CheckKeys(root, "", TopLevelKeys());

  plan.command = ReadCommand(document);
  plan.config = ReadBaseConfig(document, plan.command);
  ReadSettings(document, &plan);
  CheckCellCount(document, plan);
  plan.inputs = ReadSweepInputs(document, plan.command, dir);
  plan.fixations = ReadScoring(document.block(), plan.command);
  const ParamBlock slurm = document.block().Child("slurm");
  ReadFields(slurm, SlurmSettings::Fields(), &plan.slurm);
  slurm.CheckNoUnknownKeys();
  return plan;
}

}  // namespace attend
