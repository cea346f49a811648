// Steps 2 and 3 of planning a sweep (app/sweep_plan.h), and what each cell runs.
#include "app/sweep_plan.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>

#include "app/sweep_inputs.h"
#include "config/param_block.h"
#include "eval/fixation_data.h"
#include "io/tracking_files.h"
#include "pipeline/options_io.h"
#include "util/error.h"
#include "util/frame_range.h"
#include "util/strings.h"

namespace attend {

namespace {

namespace fs = std::filesystem;

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

// Each value of `lists` on its own over the fixed sets, so that an error names its line.
void CheckValues(const SweepPlan& plan, const std::vector<SweptList>& lists,
                 const std::string& section) {
  for (const SweptList& swept : lists) {
    for (std::size_t v = 0; v < swept.values.size(); ++v) {
      std::vector<std::string> sets = plan.sets;
      sets.push_back(swept.key + "=" + swept.values[v]);
      try {
        CheckConfiguration(plan.command, plan.config, sets);
      } catch (const ConfigError& e) {
        throw ConfigError(swept.where[v] + ": " + section + "." + swept.key + ": " + e.what());
      }
    }
  }
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
      if (other == suffix ||
          (other.size() > suffix.size() &&
           other.compare(other.size() - suffix.size(), suffix.size(), suffix) == 0 &&
           other[other.size() - suffix.size() - 1] == '.')) {
        unique = false;
      }
    }
    if (unique) return suffix;
  }
  return key;
}

// The input and the settings, readable, then a hash of them (the name stays when values are
// added to a list).
std::string CellName(const SweepInput& input, const std::vector<SweepSetting>& settings,
                     const std::vector<std::string>& keys) {
  std::string readable = input.name;
  std::string identity = input.name;
  for (const auto& [key, value] : settings) {
    // Appended piece by piece: "_" + a temporary trips GCC 12's -Wrestrict (a false alarm).
    readable += '_';
    readable += ShortKey(key, keys);
    readable += '=';
    readable += value;
    identity += '\n';
    identity += key;
    identity += '=';
    identity += value;
  }
  char hash[9];
  std::snprintf(hash, sizeof(hash), "%08x", static_cast<unsigned>(Fnv1a(identity) & 0xffffffffU));
  return FileSafe(readable, 100) + "-" + hash;
}

// The `--set KEY=VALUE` pairs of a cell as words.
std::vector<std::string> SetWords(const SweepPlan& plan, const SweepCell& cell) {
  std::vector<std::string> words;
  for (const std::string& set : CellSets(plan, cell)) {
    words.push_back("--set");
    words.push_back(set);
  }
  return words;
}

// attend run, scored by attend eval.
std::vector<std::vector<std::string>> RunCommands(const SweepPlan& plan, const SweepCell& cell,
                                                  const std::string& out) {
  const SweepInput& input = plan.inputs[cell.input];
  std::vector<std::string> compute = {"run", "--config", plan.config};
  const std::vector<std::string> sets = SetWords(plan, cell);
  compute.insert(compute.end(), sets.begin(), sets.end());
  const std::vector<std::string> source = SourceArguments(input);
  compute.insert(compute.end(), source.begin(), source.end());
  if (!input.frames.empty()) compute.insert(compute.end(), {"--frames", input.frames});
  compute.insert(compute.end(), {"--out", out, "--overwrite", "--quiet"});
  std::vector<std::string> score = {"eval", out};
  if (!input.gt.empty()) score.insert(score.end(), {"--gt", input.gt});
  return {compute, score};
}

// attend track from the ground truth's box on the first frame, scored by eval-tracking.
std::vector<std::vector<std::string>> TrackCommands(const SweepPlan& plan, const SweepCell& cell,
                                                    const std::string& out) {
  const SweepInput& input = plan.inputs[cell.input];
  const std::vector<cv::Rect2d> truth = ReadOtbGroundTruth(input.gt);
  const int first = input.frames.empty() ? 0 : ParseFrameRange(input.frames).first;
  if (first >= static_cast<int>(truth.size()) || truth[first].area() <= 0) {
    throw InputError(input.gt + ": no box for frame " + std::to_string(first) +
                     " to start the tracker on");
  }
  const cv::Rect2d& box = truth[first];
  const std::string init = std::to_string(static_cast<int>(std::lround(box.x))) + "," +
                           std::to_string(static_cast<int>(std::lround(box.y))) + "," +
                           std::to_string(static_cast<int>(std::lround(box.width))) + "," +
                           std::to_string(static_cast<int>(std::lround(box.height)));
  std::vector<std::string> compute = {"track"};
  const std::vector<std::string> source = SourceArguments(input);
  compute.insert(compute.end(), source.begin(), source.end());
  compute.insert(compute.end(), {"--init", init});
  const std::vector<std::string> sets = SetWords(plan, cell);
  compute.insert(compute.end(), sets.begin(), sets.end());
  if (!input.frames.empty()) compute.insert(compute.end(), {"--frames", input.frames});
  compute.insert(compute.end(), {"--out", out, "--overwrite"});
  std::vector<std::string> score = {
      "eval-tracking", (fs::path(out) / "tracks.csv").string(), "--gt", input.gt, "--id", "1"};
  if (!input.frames.empty()) score.insert(score.end(), {"--frames", input.frames});
  return {compute, score};
}

// attend saliency over the split's images, scored by eval-fixations with the sweep's options.
std::vector<std::vector<std::string>> SaliencyCommands(const SweepPlan& plan, const SweepCell& cell,
                                                       const std::string& out) {
  const SweepInput& input = plan.inputs[cell.input];
  const FixationDataset dataset = OpenFixationDataset(input.path);
  std::vector<FixationItem> items = dataset.items;
  items.erase(items.begin(), items.begin() + std::min<std::size_t>(input.skip, items.size()));
  if (input.first > 0 && static_cast<int>(items.size()) > input.first) items.resize(input.first);
  if (items.empty()) throw InputError(input.path + ": no images left after skip and first");
  const std::string maps = (fs::path(out) / "maps").string();
  std::vector<std::string> compute = {"saliency"};
  for (const FixationItem& item : items) compute.push_back(item.stimulus_path);
  compute.insert(compute.end(), {"--config", plan.config});
  const std::vector<std::string> sets = SetWords(plan, cell);
  compute.insert(compute.end(), sets.begin(), sets.end());
  compute.insert(compute.end(), {"--out", maps, "--quiet"});
  const FixationScoring& scoring = plan.fixations;
  std::vector<std::string> score = {"eval-fixations",  "attend=" + maps,
                                    "--dataset",       input.path,
                                    "--skip",          std::to_string(input.skip),
                                    "--first",         std::to_string(input.first),
                                    "--sigma",         ShortestNumber(scoring.sigma),
                                    "--max-side",      std::to_string(scoring.max_side),
                                    "--baseline-blur", ShortestNumber(scoring.baseline_blur)};
  if (!scoring.baselines.empty()) {
    score.push_back("--baselines");
    score.insert(score.end(), scoring.baselines.begin(), scoring.baselines.end());
  }
  score.insert(score.end(), {"--out", (fs::path(out) / "scores").string(), "--quiet"});
  return {compute, score};
}

// The base configuration with the fixed sets, read once, each configuration's values then set
// over it in turn. Every configuration sets the same keys, so the root then holds the base,
// the sets and that configuration's values, as a fresh read would. Parsing the base file is
// what planning cost: yaml-cpp took 1.5 ms for configs/default.yaml (13 KB), once a cell,
// 15 s for 10^4 cells, and as much again when the folder was prepared.
class Configurator {
 public:
  explicit Configurator(const SweepPlan& plan)
      : root_(plan.command == SweepCommand::kTrack ? ParamBlock::Parse("", "--set")
                                                   : ParamBlock::LoadFile(plan.config)) {
    for (const std::string& set : plan.sets) root_.Override(set);
  }
  AttendOptions Options(const std::vector<SweepSetting>& settings) {
    for (const auto& [key, value] : settings) root_.Override(key + "=" + value);
    return ReadOptions(root_);
  }

 private:
  ParamBlock root_;
};

}  // namespace

void CheckSweepSettings(const SweepPlan& plan) {
  try {
    CheckConfiguration(plan.command, plan.config, plan.sets);
  } catch (const ConfigError& e) {
    // Without set:, the error is the base configuration's own (it names its file and line).
    if (plan.sets_where.empty()) throw;
    throw ConfigError(plan.sets_where + ": set: " + e.what());
  }
  CheckValues(plan, plan.grid, "grid");
  for (const auto& group : plan.zips) CheckValues(plan, group, "zip");
  auto configurator = std::make_unique<Configurator>(plan);
  for (const auto& settings : SweepConfigurations(plan)) {
    try {
      configurator->Options(settings);
      continue;
    } catch (const ConfigError&) {
      // Read again from the file, for the message of a fresh read; the root that refused may
      // hold part of the settings: a new one for the next configuration.
      configurator = std::make_unique<Configurator>(plan);
    }
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
}

std::vector<std::string> ConfigurationYamls(const SweepPlan& plan) {
  Configurator configurator(plan);
  std::vector<std::string> yamls;
  for (const auto& settings : SweepConfigurations(plan)) {
    yamls.push_back(OptionsToYaml(configurator.Options(settings)));
  }
  return yamls;
}

std::vector<std::vector<SweepSetting>> SweepConfigurations(const SweepPlan& plan) {
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
  for (const SweptList& swept : plan.grid) {
    std::vector<std::vector<SweepSetting>> choices;
    for (const std::string& value : swept.values) choices.push_back({{swept.key, value}});
    cross(choices);
  }
  for (const auto& group : plan.zips) {
    std::vector<std::vector<SweepSetting>> choices;
    for (std::size_t step = 0; step < group[0].values.size(); ++step) {
      std::vector<SweepSetting> choice;
      for (const SweptList& swept : group) choice.push_back({swept.key, swept.values[step]});
      choices.push_back(std::move(choice));
    }
    cross(choices);
  }
  return configurations;
}

std::vector<SweepCell> ExpandCells(const SweepPlan& plan) {
  std::vector<SweepCell> cells;
  int configuration = 0;
  for (const auto& settings : SweepConfigurations(plan)) {
    ++configuration;
    for (std::size_t i = 0; i < plan.inputs.size(); ++i) {
      SweepCell cell;
      cell.index = static_cast<int>(cells.size());
      cell.input = static_cast<int>(i);
      cell.settings = settings;
      cell.configuration = configuration - 1;
      cell.name = CellName(plan.inputs[i], settings, plan.keys);
      cells.push_back(std::move(cell));
    }
  }
  return cells;
}

SweepPlan PlanSweep(const std::string& path, const SweepReadOptions& options) {
  SweepPlan plan = ReadSweepFile(path, options);
  CheckSweepSettings(plan);
  plan.cells = ExpandCells(plan);
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

std::vector<std::vector<std::string>> CellCommands(const SweepPlan& plan, const SweepCell& cell,
                                                   const std::string& cell_dir) {
  const std::string out = (fs::path(cell_dir) / "out").string();
  switch (plan.command) {
    case SweepCommand::kRun:
      return RunCommands(plan, cell, out);
    case SweepCommand::kTrack:
      return TrackCommands(plan, cell, out);
    case SweepCommand::kSaliency:
      return SaliencyCommands(plan, cell, out);
  }
  return {};
}

}  // namespace attend
