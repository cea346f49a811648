#include "app/sweep_folder.h"

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>

#include "app/render_scene.h"
#include "app/sweep_records.h"
#include "util/error.h"
#include "util/file_checks.h"
#include "util/folder_lock.h"
#include "util/json_text.h"
#include "util/output_folder.h"
#include "util/strings.h"
#include "util/subprocess.h"

namespace attend {

namespace {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

Json SettingsJson(const std::vector<SweepSetting>& settings) {
  Json json = Json::object();
  for (const auto& [key, value] : settings) json[key] = value;
  return json;
}

Json InputJson(const SweepInput& input) {
  Json json = {{"name", input.name}, {"kind", input.kind}, {"path", input.path}};
  if (!input.right.empty()) json["right"] = input.right;
  if (!input.gt.empty()) json["gt"] = input.gt;
  if (!input.frames.empty()) json["frames"] = input.frames;
  if (input.kind == "fixations") {
    json["skip"] = input.skip;
    json["first"] = input.first;
  }
  return json;
}

Json SlurmJson(const SlurmSettings& slurm) {
  return {{"partition", slurm.partition},
          {"time", slurm.time},
          {"mem", slurm.mem},
          {"cpus_per_task", slurm.cpus_per_task},
          {"throttle", slurm.throttle}};
}

// The cell.json of a planned cell, and what must match for a folder's cell to be the same.
struct PlannedCell {
  Json json;
  std::vector<std::vector<std::string>> commands;
  std::string config;  // its effective configuration
};

PlannedCell PlanCell(const SweepPlan& plan, const SweepCell& cell, const fs::path& cell_dir,
                     const std::string& config) {
  PlannedCell planned;
  const std::vector<std::vector<std::string>> commands =
      CellCommands(plan, cell, cell_dir.string());
  planned.commands = commands;
  Json command_json = Json::array();
  Json lines = Json::array();
  for (const std::vector<std::string>& command : commands) {
    command_json.push_back(command);
    std::vector<std::string> words = {"attend"};
    words.insert(words.end(), command.begin(), command.end());
    lines.push_back(ShellQuote(words));
  }
  planned.json = {{"name", cell.name},
                  {"input", InputJson(plan.inputs[cell.input])},
                  {"settings", SettingsJson(cell.settings)},
                  {"sets", CellSets(plan, cell)},
                  {"command", SweepCommandName(plan.command)},
                  {"config", plan.config},
                  {"commands", command_json},
                  {"reproduce", lines}};
  planned.config = config;
  return planned;
}

Json StoredCellJson(const StoredCell& cell) {
  return {{"index", cell.index},
          {"name", cell.name},
          {"input", cell.input},
          {"settings", SettingsJson(cell.settings)}};
}

void WriteSweepJson(const SweepPlan& plan, const fs::path& dir,
                    const std::vector<StoredCell>& cells) {
  Json inputs = Json::array();
  for (const SweepInput& input : plan.inputs) inputs.push_back(InputJson(input));
  Json cell_list = Json::array();
  for (const StoredCell& cell : cells) cell_list.push_back(StoredCellJson(cell));
  const Json json = {{"attend_version", ATTEND_VERSION},
                     {"sweep_file", plan.file},
                     {"command", SweepCommandName(plan.command)},
                     {"config", plan.config},
                     {"sets", plan.sets},
                     {"keys", plan.keys},
                     {"key_groups", plan.groups},
                     {"inputs", inputs},
                     {"slurm", SlurmJson(plan.slurm)},
                     {"cells", cell_list}};
  ReplaceFileText((dir / "sweep.json").string(), JsonText(json, 2) + "\n", "the sweep's record");
}

// The scene inputs not yet rendered, each rendered beside its folder and renamed into place
// (a stopped render leaves no folder that looks finished).
void RenderScenes(const SweepPlan& plan) {
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

// A cell DIR holds must run the commands and the configuration planned for it now.
void CheckSameCell(const SweepPlan& plan, const fs::path& dir, const SweepCell& cell,
                   const PlannedCell& planned) {
  const fs::path cell_dir = dir / "cells" / cell.name;
  std::vector<std::vector<std::string>> commands;
  try {
    commands = SweepRecord::Load((cell_dir / "cell.json").string()).StringLists("commands");
  } catch (const InputError& e) {
    throw InputError(std::string(e.what()) + "; remove the folder " + cell_dir.string() +
                     " to run the cell again");
  }
  const bool same_commands = commands == planned.commands;
  const bool same_config = ReadFileText(cell_dir / "config.yaml") == planned.config;
  if (!same_commands || !same_config) {
    throw ConfigError(plan.file + ": the cell " + cell.name + " in " + dir.string() +
                      " would now run " +
                      (same_commands ? "with another effective configuration (the base "
                                       "configuration file changed)"
                                     : "other commands (the base configuration, set, "
                                       "inputs or scoring changed)") +
                      ": that is another sweep; give another --out");
  }
}

// The planned cells whose folders DIR lacks, with their cell.json: new cells, and cells of the
// folder's sweep.json whose folder (or its cell.json) is missing: removed by hand, vanished
// while it ran, or never written when a full disk stopped the folder's preparation. A cell DIR
// holds must run as planned; new cells, and cells of DIR the plan no longer has, need
// `extend`.
struct MissingCells {
  std::vector<std::pair<const SweepCell*, PlannedCell>> added;      // new to the sweep
  std::vector<std::pair<const SweepCell*, PlannedCell>> recreated;  // in sweep.json already
};

MissingCells FindMissingCells(const SweepPlan& plan, const fs::path& dir,
                              const std::vector<StoredCell>& cells, bool extend,
                              std::vector<std::string>* notes) {
  std::map<std::string, const StoredCell*> by_name;
  for (const StoredCell& cell : cells) by_name[cell.name] = &cell;
  MissingCells missing;
  std::set<std::string> planned_names;
  const std::vector<std::string> configs = ConfigurationYamls(plan);
  for (const SweepCell& cell : plan.cells) {
    planned_names.insert(cell.name);
    const fs::path cell_dir = dir / "cells" / cell.name;
    PlannedCell planned = PlanCell(plan, cell, cell_dir, configs.at(cell.configuration));
    if (by_name.count(cell.name) == 0) {
      missing.added.emplace_back(&cell, std::move(planned));
      continue;
    }
    std::error_code error;
    if (!fs::exists(cell_dir / "cell.json", error)) {
      missing.recreated.emplace_back(&cell, std::move(planned));
      continue;
    }
    CheckSameCell(plan, dir, cell, planned);
  }
  const auto& added = missing.added;
  if (!cells.empty() && !added.empty() && !extend) {
    throw ConfigError(plan.file + ": changed since " + dir.string() + " was made: " +
                      std::to_string(added.size()) + " cells are new (the first: " +
                      added.front().first->name +
                      "); give --extend to add them to the sweep, or another --out");
  }
  int dropped = 0;
  for (const StoredCell& cell : cells) dropped += planned_names.count(cell.name) == 0 ? 1 : 0;
  if (dropped > 0) {
    if (!extend) {
      throw ConfigError(plan.file + ": changed since " + dir.string() + " was made: " +
                        std::to_string(dropped) +
                        " of its cells are no longer in the file; give --extend to keep them "
                        "and run the file's, or another --out");
    }
    notes->push_back(std::to_string(dropped) +
                     " cells of the folder are no longer in the sweep file; they are kept");
  }
  if (cells.size() + added.size() > static_cast<std::size_t>(kMaxSweepCells)) {
    throw ConfigError(plan.file + ": " + std::to_string(added.size()) + " new cells beside the " +
                      std::to_string(cells.size()) + " of " + dir.string() +
                      " would be more than the " + std::to_string(kMaxSweepCells) +
                      " a sweep may have (docs/LIMITS.md); give another --out");
  }
  return missing;
}

// Writes a cell's folder: config.yaml, then cell.json (a folder with cell.json is complete).
void WriteCellFolder(const fs::path& cell_dir, const PlannedCell& planned, int index) {
  std::error_code error;
  fs::create_directories(cell_dir, error);
  if (error) {
    throw OutputError(cell_dir.string() + ": cannot create the folder: " + error.message());
  }
  Json json = planned.json;
  json["index"] = index;
  json["attend_version"] = ATTEND_VERSION;
  ReplaceFileText((cell_dir / "config.yaml").string(), planned.config, "the cell's configuration");
  ReplaceFileText((cell_dir / "cell.json").string(), JsonText(json, 2) + "\n", "the cell's record");
}

}  // namespace

std::vector<std::vector<std::string>> ReadCellCommands(const StoredSweep& sweep,
                                                       const StoredCell& cell) {
  const SweepRecord record = SweepRecord::Load((fs::path(sweep.CellDir(cell)) / "cell.json").string());
  const std::vector<std::vector<std::string>> commands = record.StringLists("commands");
  if (commands.empty()) record.Fail("commands", "no command");
  for (const std::vector<std::string>& command : commands) {
    if (command.empty() || command[0].empty()) record.Fail("commands", "an empty command");
  }
  return commands;
}

bool IsEmptyOrScenesOnly(const std::string& dir) {
  std::error_code error;
  if (!fs::exists(dir, error)) return true;
  if (!fs::is_directory(dir, error)) return false;
  // What a preparation stopped before sweep.json (a full disk, a kill) leaves: the rendered
  // scenes, the copy of the sweep file and the folder's lock.
  for (const auto& entry : fs::directory_iterator(dir, error)) {
    const std::string name = entry.path().filename().string();
    if (name != "scenes" && name != "sweep.yaml" && name != FolderLock::kFileName &&
        name != ".lock") {
      return false;
    }
  }
  return true;
}

std::string StoredSweep::CellDir(const StoredCell& cell) const {
  return (fs::path(dir) / "cells" / cell.name).string();
}

const char* CellStateName(CellState state) {
  switch (state) {
    case CellState::kWaiting:
      return "waiting";
    case CellState::kRunning:
      return "running";
    case CellState::kDone:
      return "done";
    case CellState::kFailed:
      return "failed";
    case CellState::kKilled:
      return "killed";
    case CellState::kInterrupted:
      return "interrupted";
  }
  return "waiting";
}

StoredSweep PrepareSweepFolder(const SweepPlan& plan, const std::string& dir_text, bool extend,
                               std::vector<std::string>* notes) {
  const fs::path dir = fs::absolute(dir_text).lexically_normal();
  std::error_code error;
  std::vector<StoredCell> cells;
  if (fs::exists(dir / "sweep.json", error)) {
    const StoredSweep stored = LoadSweepFolder(dir.string());
    cells = stored.cells;
  } else if (!IsEmptyOrScenesOnly(dir)) {
    throw OutputError(dir.string() + ": not empty and not a sweep folder (no sweep.json)");
  }
  fs::create_directories(dir / "cells", error);
  if (error) throw OutputError(dir.string() + ": cannot create the folder: " + error.message());
  MissingCells missing = FindMissingCells(plan, dir, cells, extend, notes);
  RenderScenes(plan);
  // sweep.json first, then the cell folders: a preparation stopped between them (a full disk)
  // leaves a sweep folder whose missing cell folders the same command writes again.
  std::vector<std::pair<const PlannedCell*, int>> to_write;
  for (auto& [cell, planned] : missing.added) {
    StoredCell stored;
    stored.index = static_cast<int>(cells.size());
    stored.name = cell->name;
    stored.input = plan.inputs[cell->input].name;
    stored.settings = cell->settings;
    to_write.emplace_back(&planned, stored.index);
    cells.push_back(std::move(stored));
  }
  std::map<std::string, int> index_of;
  for (const StoredCell& cell : cells) index_of[cell.name] = cell.index;
  for (auto& [cell, planned] : missing.recreated) {
    to_write.emplace_back(&planned, index_of.at(cell->name));
  }
  ReplaceFileText((dir / "sweep.yaml").string(), plan.text, "the copy of the sweep file");
  WriteSweepJson(plan, dir, cells);
  for (const auto& [planned, index] : to_write) {
    WriteCellFolder(dir / "cells" / cells[index].name, *planned, index);
  }
  if (!missing.recreated.empty()) {
    notes->push_back(std::to_string(missing.recreated.size()) +
                     " cell folders were missing or had no cell.json (the first: " +
                     missing.recreated.front().first->name + "); written again");
  }
  if (!cells.empty() && !missing.added.empty() && extend) {
    notes->push_back(std::to_string(missing.added.size()) + " cells added to the sweep");
  }
  return LoadSweepFolder(dir.string());
}

StoredSweep LoadSweepFolder(const std::string& dir_text) {
  const fs::path dir = fs::absolute(dir_text).lexically_normal();
  std::error_code error;
  if (!fs::is_regular_file(dir / "sweep.json", error)) {
    throw InputError(dir_text + ": not a sweep folder (no sweep.json)");
  }
  const SweepRecord json = SweepRecord::Load((dir / "sweep.json").string());
  StoredSweep sweep;
  sweep.dir = dir.string();
  sweep.file = json.String("sweep_file");
  sweep.command = json.String("command");
  if (sweep.command != "run" && sweep.command != "track" && sweep.command != "saliency") {
    json.Fail("command", "'" + sweep.command + "' is not one of run, track, saliency");
  }
  sweep.keys = json.Strings("keys");
  sweep.groups = json.IntLists("key_groups", {});
  for (const std::vector<int>& group : sweep.groups) {
    for (const int key : group) {
      if (key >= static_cast<int>(sweep.keys.size())) json.Fail("key_groups", "a key out of range");
    }
  }
  const SweepRecord slurm = json.Object("slurm");
  sweep.slurm.partition = slurm.String("partition");
  sweep.slurm.time = slurm.String("time");
  sweep.slurm.mem = slurm.String("mem");
  sweep.slurm.cpus_per_task = static_cast<int>(slurm.Integer("cpus_per_task", 1, 1024));
  sweep.slurm.throttle = static_cast<int>(slurm.Integer("throttle", 0, 100000));
  const std::vector<SweepRecord> entries = json.Objects("cells");
  if (entries.size() > static_cast<std::size_t>(kMaxSweepCells)) {
    json.Fail("cells", std::to_string(entries.size()) + " cells, more than the " +
                           std::to_string(kMaxSweepCells) + " a sweep may have");
  }
  for (const SweepRecord& entry : entries) {
    StoredCell cell;
    cell.index = static_cast<int>(entry.Integer("index", 0, kMaxSweepCells));
    cell.name = entry.String("name");
    // The name is a folder below cells/: never a path elsewhere.
    if (cell.name.empty() || FileSafe(cell.name, cell.name.size()) != cell.name) {
      entry.Fail("name", "'" + cell.name + "' is not a cell folder's name");
    }
    cell.input = entry.String("input");
    cell.settings = entry.StringMap("settings");
    if (cell.index != static_cast<int>(sweep.cells.size())) {
      entry.Fail("index", std::to_string(cell.index) + " out of order (expected " +
                              std::to_string(sweep.cells.size()) + ")");
    }
    sweep.cells.push_back(std::move(cell));
  }
  return sweep;
}

CellStatus ReadCellStatus(const StoredSweep& sweep, const StoredCell& cell) {
  const fs::path path = fs::path(sweep.CellDir(cell)) / "status.json";
  std::error_code error;
  if (!fs::exists(path, error)) return CellStatus();
  return ParseCellStatus(
      ReadRegularFile(path.string(), "the cell's status", ExitStatus::kBadInput,
                      kMaxSweepRecordBytes),
      path.string());
}

std::vector<std::pair<std::string, double>> ReadCellScores(const StoredSweep& sweep,
                                                           const StoredCell& cell) {
  const fs::path path = fs::path(sweep.CellDir(cell)) / "scores.json";
  return ParseCellScores(ReadRegularFile(path.string(), "the cell's scores", ExitStatus::kBadInput,
                                         kMaxSweepRecordBytes),
                         path.string());
}

}  // namespace attend
