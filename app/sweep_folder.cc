#include "app/sweep_folder.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <csignal>
#include <cstring>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "util/error.h"
#include "util/json_text.h"
#include "util/output_folder.h"
#include "util/strings.h"
#include "util/subprocess.h"
#include "util/timer.h"

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

// The child running a cell's command, and the signal that asked the cell to stop; a signal
// handler can only reach globals.
std::atomic<pid_t> g_command_pid{0};
std::atomic<int> g_cell_signal{0};

extern "C" void OnCellSignal(int signal) {
  g_cell_signal.store(signal);
  const pid_t child = g_command_pid.load();
  if (child > 0) kill(child, signal);
}

// The last "attend: error: " line of a command's standard error, else its last line.
std::string ErrorMessage(const std::string& err) {
  std::istringstream lines(err);
  std::string line, last, error;
  while (std::getline(lines, line)) {
    if (line.empty()) continue;
    last = line;
    if (line.rfind("attend: error: ", 0) == 0) error = line.substr(15);
  }
  return error.empty() ? last : error;
}

// Numbers below `json`, their keys joined by '.', skipping `skip` at the top.
void Flatten(const Json& json, const std::string& prefix,
             const std::set<std::string>& skip, std::vector<std::pair<std::string, double>>* out) {
  for (const auto& [key, value] : json.items()) {
    if (prefix.empty() && skip.count(key) != 0) continue;
    const std::string name = prefix.empty() ? key : prefix + "." + key;
    if (value.is_object()) {
      Flatten(value, name, {}, out);
    } else if (value.is_number()) {
      out->emplace_back(name, value.get<double>());
    } else if (value.is_boolean()) {
      out->emplace_back(name, value.get<bool>() ? 1.0 : 0.0);
    }
  }
}

// The scores of a finished cell from what its scorer wrote.
Json CellScores(const std::string& command, const fs::path& cell_dir, const std::string& out) {
  std::vector<std::pair<std::string, double>> scores;
  if (command == "run") {
    Flatten(Json::parse(out), "", {"run", "gt", "per_object"}, &scores);
  } else if (command == "track") {
    const nlohmann::json report = nlohmann::json::parse(out);
    const nlohmann::json& target = report.at("targets").at(0);
    for (const char* key : {"success_auc", "precision_20", "mean_iou", "frames", "found"}) {
      scores.emplace_back(key, target.at(key).get<double>());
    }
    const nlohmann::json track = nlohmann::json::parse(ReadFileText(cell_dir / "out" / "track.json"));
    if (track.contains("ms_per_frame")) {
      scores.emplace_back("ms_per_frame", track["ms_per_frame"].get<double>());
    }
  } else {
    const nlohmann::json report =
        nlohmann::json::parse(ReadFileText(cell_dir / "out" / "scores" / "fixations.json"));
    for (const auto& [method, entry] : report.at("methods").items()) {
      for (const auto& [metric, value] : entry.items()) {
        if (!value.is_object() || !value.contains("mean")) continue;
        const std::string name = method == "attend" ? metric : method + "." + metric;
        scores.emplace_back(name, value["mean"].is_number() ? value["mean"].get<double>()
                                                            : std::nan(""));
      }
    }
  }
  Json json = Json::object();
  for (const auto& [key, value] : scores) {
    json[key] = std::isfinite(value) ? Json(value) : Json();
  }
  return json;
}

void WriteStatus(const fs::path& cell_dir, const Json& status) {
  ReplaceFileText((cell_dir / "status.json").string(), JsonText(status, 2) + "\n");
}

}  // namespace

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

  // The planned cells against those in the folder.
  std::map<std::string, const StoredCell*> by_name;
  for (const StoredCell& cell : cells) by_name[cell.name] = &cell;
  std::vector<std::pair<const SweepCell*, PlannedCell>> added;
  std::set<std::string> planned_names;
  for (const SweepCell& cell : plan.cells) {
    planned_names.insert(cell.name);
    const fs::path cell_dir = dir / "cells" / cell.name;
    PlannedCell planned = PlanCell(plan, cell, cell_dir);
    if (by_name.count(cell.name) != 0) {
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

int RunCell(const std::string& dir, int index) {
  const StoredSweep sweep = LoadSweepFolder(dir);
  if (index < 0 || index >= static_cast<int>(sweep.cells.size())) {
    throw ConfigError("--cell " + std::to_string(index) + ": " + dir + " has cells 0 to " +
                      std::to_string(sweep.cells.size() - 1));
  }
  const StoredCell& cell = sweep.cells[index];
  const fs::path cell_dir = sweep.CellDir(cell);
  const Json description = ReadJson(cell_dir / "cell.json");
  std::error_code error;
  fs::create_directories(cell_dir / "logs", error);
  fs::remove(cell_dir / "scores.json", error);

  const char* job = std::getenv("SLURM_ARRAY_JOB_ID");
  const char* task = std::getenv("SLURM_ARRAY_TASK_ID");
  const bool in_slurm = job != nullptr && task != nullptr;
  Json status = {{"state", "running"},
                 {"cell", cell.name},
                 {"index", index},
                 {"executor", in_slurm ? "slurm" : "local"},
                 {"host", HostName()},
                 {"pid", static_cast<long>(getpid())},
                 {"started", UtcTimestamp()}};
  if (in_slurm) status["slurm_task"] = std::string(job) + "_" + task;
  WriteStatus(cell_dir, status);

  g_cell_signal.store(0);
  std::signal(SIGINT, OnCellSignal);
  std::signal(SIGTERM, OnCellSignal);
  const Stopwatch watch;
  const std::string program = SelfExecutable();
  const std::vector<std::vector<std::string>> commands =
      description.at("commands").get<std::vector<std::vector<std::string>>>();
  std::string scorer_out;
  const auto finish = [&](const std::string& state, int exit_status, const std::string& message) {
    status["state"] = state;
    status["exit_status"] = exit_status;
    if (!message.empty()) status["message"] = message;
    status["finished"] = UtcTimestamp();
    status["seconds"] = watch.ElapsedMs() / 1000.0;
    WriteStatus(cell_dir, status);
    return exit_status;
  };
  for (std::size_t step = 0; step < commands.size(); ++step) {
    if (g_cell_signal.load() != 0) break;
    std::vector<std::string> argv = {program};
    argv.insert(argv.end(), commands[step].begin(), commands[step].end());
    const std::string log =
        (cell_dir / "logs" / (std::to_string(step + 1) + "-" + commands[step][0])).string();
    std::string start_error;
    const pid_t pid = StartProcess(argv, log + ".out", log + ".err", &start_error, true);
    if (pid < 0) return finish("failed", 1, "cannot start " + program + ": " + start_error);
    g_command_pid.store(pid);
    // A signal that came before the pid was known still reaches the command.
    if (g_cell_signal.load() != 0) kill(pid, g_cell_signal.load());
    const ProcessExit exit = WaitProcess(pid);
    g_command_pid.store(0);
    if (exit.Status() != 0 || g_cell_signal.load() != 0) {
      const int signal = g_cell_signal.load();
      if (signal != 0) {
        const std::string cause = std::string(strsignal(signal)) + " during " + commands[step][0];
        return in_slurm ? finish("killed", 128 + signal,
                                 "stopped by Slurm (" + cause +
                                     "): a time limit, scancel or preemption")
                        : finish("interrupted", 128 + signal, cause);
      }
      if (exit.signal != 0) {
        return finish("killed", exit.Status(),
                      commands[step][0] + " was killed by " + strsignal(exit.signal));
      }
      const std::string message = ErrorMessage(ReadFileText(log + ".err"));
      return finish("failed", exit.code, commands[step][0] + ": " + message);
    }
    if (step + 1 == commands.size()) scorer_out = ReadFileText(log + ".out");
  }
  if (g_cell_signal.load() != 0) {
    const int signal = g_cell_signal.load();
    return finish(in_slurm ? "killed" : "interrupted", 128 + signal, strsignal(signal));
  }
  Json scores;
  try {
    scores = CellScores(sweep.command, cell_dir, scorer_out);
  } catch (const std::exception& e) {
    return finish("failed", 1, std::string("the scores cannot be read: ") + e.what());
  }
  ReplaceFileText((cell_dir / "scores.json").string(), JsonText(scores, 2) + "\n");
  return finish("done", 0, "");
}

LocalSweepResult RunSweepLocally(const StoredSweep& sweep, const std::vector<int>& indexes,
                                 int jobs, const std::atomic<int>* stop,
                                 const std::function<void(const LocalProgress&)>& on_progress) {
  const fs::path lock_path = fs::path(sweep.dir) / ".lock";
  const int lock = open(lock_path.c_str(), O_RDWR | O_CREAT, 0644);
  if (lock < 0 || flock(lock, LOCK_EX | LOCK_NB) != 0) {
    if (lock >= 0) close(lock);
    throw OutputError(sweep.dir + ": another attend sweep is running this folder on this machine");
  }
  LocalSweepResult result;
  LocalProgress& progress = result.progress;
  progress.total = static_cast<int>(indexes.size());
  const Stopwatch watch;
  const std::string program = SelfExecutable();
  std::map<pid_t, int> running;  // pid to cell index
  std::size_t next = 0;
  int forwarded = 0;
  while (next < indexes.size() || !running.empty()) {
    const int signal = stop != nullptr ? stop->load() : 0;
    if (signal != 0 && forwarded == 0) {
      for (const auto& [pid, index] : running) kill(pid, signal);
      forwarded = signal;
      result.stop_signal = signal;
    }
    while (signal == 0 && next < indexes.size() && static_cast<int>(running.size()) < jobs) {
      const int index = indexes[next++];
      const StoredCell& cell = sweep.cells[index];
      const fs::path logs = fs::path(sweep.CellDir(cell)) / "logs";
      std::error_code error;
      fs::create_directories(logs, error);
      std::string start_error;
      const pid_t pid = StartProcess(
          {program, "sweep", sweep.dir, "--cell", std::to_string(index)},
          (logs / "cell.out").string(), (logs / "cell.err").string(), &start_error, true);
      if (pid < 0) {
        close(lock);
        throw InternalError("cannot start a cell: " + start_error);
      }
      running[pid] = index;
    }
    progress.running = static_cast<int>(running.size());
    progress.elapsed_s = watch.ElapsedMs() / 1000.0;
    if (on_progress) on_progress(progress);
    if (running.empty()) break;
    // Polled, so that a stop signal is passed on at once whatever the cells are doing.
    int status = 0;
    const pid_t pid = waitpid(-1, &status, WNOHANG);
    if (pid <= 0) {
      usleep(50000);
      continue;
    }
    const auto found = running.find(pid);
    if (found == running.end()) continue;
    const CellStatus cell = ReadCellStatus(sweep, sweep.cells[found->second]);
    running.erase(found);
    if (cell.state == CellState::kDone) {
      ++progress.done;
      progress.cell_seconds += cell.seconds;
    } else if (cell.state == CellState::kFailed || cell.state == CellState::kKilled) {
      ++progress.failed;
      progress.cell_seconds += cell.seconds;
    }
  }
  progress.running = 0;
  progress.elapsed_s = watch.ElapsedMs() / 1000.0;
  if (on_progress) on_progress(progress);
  close(lock);
  return result;
}

}  // namespace attend
