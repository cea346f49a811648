#include "app/sweep_folder.h"

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>

#include "app/render_scene.h"
#include "util/error.h"
#include "util/json_text.h"
#include "util/output_folder.h"
#include "util/strings.h"
#include "util/subprocess.h"

namespace attend {

namespace {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

Json ReadJson(const fs::path& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path.string() + ": cannot be read");
  try {
    return Json::parse(in);
  } catch (const std::exception& e) {
    throw InputError(path.string() + ": not valid JSON (" + e.what() + ")");
  }
}

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
  std::string config;  // its effective configuration
};

PlannedCell PlanCell(const SweepPlan& plan, const SweepCell& cell, const fs::path& cell_dir) {
  PlannedCell planned;
  const std::vector<std::vector<std::string>> commands =
      CellCommands(plan, cell, cell_dir.string());
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
  planned.config = CellConfigYaml(plan, cell);
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
  ReplaceFileText((dir / "sweep.json").string(), JsonText(json, 2) + "\n");
}

std::vector<SweepSetting> ReadSettings(const Json& json) {
  std::vector<SweepSetting> settings;
  for (const auto& [key, value] : json.items()) settings.emplace_back(key, value.get<std::string>());
  return settings;
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
  const std::string old_json = ReadFileText(cell_dir / "cell.json");
  Json old;
  try {
    old = Json::parse(old_json);
  } catch (const std::exception&) {
    throw InputError((cell_dir / "cell.json").string() + ": missing or not valid JSON");
  }
  const bool same_commands = old.value("commands", Json()) == planned.json["commands"];
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

// The planned cells that DIR does not hold yet, with their cell.json. A cell DIR holds must run
// as planned; new cells, and cells of DIR the plan no longer has, need `extend`.
std::vector<std::pair<const SweepCell*, PlannedCell>> NewCells(
    const SweepPlan& plan, const fs::path& dir, const std::vector<StoredCell>& cells, bool extend,
    std::vector<std::string>* notes) {
  std::map<std::string, const StoredCell*> by_name;
  for (const StoredCell& cell : cells) by_name[cell.name] = &cell;
  std::vector<std::pair<const SweepCell*, PlannedCell>> added;
  std::set<std::string> planned_names;
  for (const SweepCell& cell : plan.cells) {
    planned_names.insert(cell.name);
    const fs::path cell_dir = dir / "cells" / cell.name;
    PlannedCell planned = PlanCell(plan, cell, cell_dir);
    if (by_name.count(cell.name) != 0) {
      CheckSameCell(plan, dir, cell, planned);
      continue;
    }
    added.emplace_back(&cell, std::move(planned));
  }
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
  return added;
}

}  // namespace

std::vector<std::vector<std::string>> ReadCellCommands(const StoredSweep& sweep,
                                                       const StoredCell& cell) {
  const Json description = ReadJson(fs::path(sweep.CellDir(cell)) / "cell.json");
  return description.at("commands").get<std::vector<std::vector<std::string>>>();
}

bool IsEmptyOrScenesOnly(const std::string& dir) {
  std::error_code error;
  if (!fs::exists(dir, error)) return true;
  if (!fs::is_directory(dir, error)) return false;
  for (const auto& entry : fs::directory_iterator(dir, error)) {
    if (entry.path().filename() != "scenes") return false;
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
  auto added = NewCells(plan, dir, cells, extend, notes);
  RenderScenes(plan);
  for (auto& [cell, planned] : added) {
    StoredCell stored;
    stored.index = static_cast<int>(cells.size());
    stored.name = cell->name;
    stored.input = plan.inputs[cell->input].name;
    stored.settings = cell->settings;
    const fs::path cell_dir = dir / "cells" / cell->name;
    fs::create_directories(cell_dir, error);
    if (error) throw OutputError(cell_dir.string() + ": cannot create the folder: " + error.message());
    Json json = planned.json;
    json["index"] = stored.index;
    json["attend_version"] = ATTEND_VERSION;
    ReplaceFileText((cell_dir / "config.yaml").string(), planned.config);
    ReplaceFileText((cell_dir / "cell.json").string(), JsonText(json, 2) + "\n");
    cells.push_back(std::move(stored));
  }
  if (!cells.empty() && !added.empty() && extend) {
    notes->push_back(std::to_string(added.size()) + " cells added to the sweep");
  }
  ReplaceFileText((dir / "sweep.yaml").string(), plan.text);
  WriteSweepJson(plan, dir, cells);
  return LoadSweepFolder(dir.string());
}

StoredSweep LoadSweepFolder(const std::string& dir_text) {
  const fs::path dir = fs::absolute(dir_text).lexically_normal();
  std::error_code error;
  if (!fs::is_regular_file(dir / "sweep.json", error)) {
    throw InputError(dir_text + ": not a sweep folder (no sweep.json)");
  }
  const Json json = ReadJson(dir / "sweep.json");
  StoredSweep sweep;
  try {
    sweep.dir = dir.string();
    sweep.file = json.at("sweep_file").get<std::string>();
    sweep.command = json.at("command").get<std::string>();
    sweep.keys = json.at("keys").get<std::vector<std::string>>();
    sweep.groups = json.value("key_groups", std::vector<std::vector<int>>());
    const Json& slurm = json.at("slurm");
    sweep.slurm.partition = slurm.at("partition").get<std::string>();
    sweep.slurm.time = slurm.at("time").get<std::string>();
    sweep.slurm.mem = slurm.at("mem").get<std::string>();
    sweep.slurm.cpus_per_task = slurm.at("cpus_per_task").get<int>();
    sweep.slurm.throttle = slurm.at("throttle").get<int>();
    for (const Json& entry : json.at("cells")) {
      StoredCell cell;
      cell.index = entry.at("index").get<int>();
      cell.name = entry.at("name").get<std::string>();
      cell.input = entry.at("input").get<std::string>();
      cell.settings = ReadSettings(entry.at("settings"));
      if (cell.index != static_cast<int>(sweep.cells.size())) {
        throw InputError((dir / "sweep.json").string() + ": cell " + cell.name +
                         " out of order (index " + std::to_string(cell.index) + ")");
      }
      sweep.cells.push_back(std::move(cell));
    }
  } catch (const nlohmann::json::exception& e) {
    throw InputError((dir / "sweep.json").string() + ": not a sweep description (" + e.what() + ")");
  }
  return sweep;
}

CellStatus ReadCellStatus(const StoredSweep& sweep, const StoredCell& cell) {
  CellStatus status;
  const fs::path path = fs::path(sweep.CellDir(cell)) / "status.json";
  std::error_code error;
  if (!fs::exists(path, error)) return status;
  const Json json = ReadJson(path);
  const std::string state = json.value("state", "");
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
    throw InputError(path.string() + ": unknown state '" + state + "'");
  }
  status.exit_status = json.value("exit_status", 0);
  status.message = json.value("message", "");
  status.seconds = json.value("seconds", 0.0);
  status.host = json.value("host", "");
  status.pid = json.value("pid", 0L);
  status.executor = json.value("executor", "");
  status.slurm_task = json.value("slurm_task", "");
  return status;
}

std::vector<std::pair<std::string, double>> ReadCellScores(const StoredSweep& sweep,
                                                           const StoredCell& cell) {
  std::vector<std::pair<std::string, double>> scores;
  const fs::path path = fs::path(sweep.CellDir(cell)) / "scores.json";
  std::error_code error;
  if (!fs::exists(path, error)) return scores;
  const Json json = ReadJson(path);
  for (const auto& [key, value] : json.items()) {
    scores.emplace_back(key, value.is_number() ? value.get<double>() : std::nan(""));
  }
  return scores;
}

}  // namespace attend
