#include "app/sweep_cell.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>

#include "app/sweep_records.h"
#include "util/error.h"
#include "util/folder_lock.h"
#include "util/json_text.h"
#include "util/output_folder.h"
#include "util/strings.h"
#include "util/subprocess.h"
#include "util/timer.h"

namespace attend {

namespace {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

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
void Flatten(const Json& json, const std::string& prefix, const std::set<std::string>& skip,
             std::vector<std::pair<std::string, double>>* out) {
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
    const nlohmann::json track =
        nlohmann::json::parse(ReadFileText(cell_dir / "out" / "track.json"));
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
        scores.emplace_back(name,
                            value["mean"].is_number() ? value["mean"].get<double>() : std::nan(""));
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
  ReplaceFileText((cell_dir / "status.json").string(), JsonText(status, 2) + "\n",
                  "the cell's status");
}

bool FolderExists(const fs::path& folder) {
  std::error_code error;
  return fs::is_directory(folder, error);
}

// A cell folder whose cell.json is gone was removed while the cell ran (its command may have
// made parts of it again, such as out/).
bool Vanished(const fs::path& cell_dir) {
  std::error_code error;
  return !fs::exists(cell_dir / "cell.json", error);
}

const char* kVanished = "the cell folder vanished while it ran";

// A cell's status.json: running from the start, then how the cell ended, with its wall time.
class CellStatusFile {
 public:
  CellStatusFile(fs::path cell_dir, Json status)
      : cell_dir_(std::move(cell_dir)), status_(std::move(status)) {
    WriteStatus(cell_dir_, status_);
  }
  // Records the end; returns `exit_status`. A cell folder removed meanwhile is made again to
  // hold the record (the next `attend sweep DIR` writes its cell.json again).
  int Finish(const std::string& state, int exit_status, const std::string& message) {
    if (!FolderExists(cell_dir_)) {
      std::error_code error;
      fs::create_directories(cell_dir_, error);
    }
    status_["state"] = state;
    status_["exit_status"] = exit_status;
    if (!message.empty()) status_["message"] = message;
    status_["finished"] = UtcTimestamp();
    status_["seconds"] = watch_.ElapsedMs() / 1000.0;
    WriteStatus(cell_dir_, status_);
    return exit_status;
  }

 private:
  fs::path cell_dir_;
  Json status_;
  Stopwatch watch_;
};

// "" when each file can be created (or truncated) for writing, else which and why.
std::string CheckWritable(const std::vector<std::string>& paths) {
  for (const std::string& path : paths) {
    const int fd = open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd < 0) return "cannot write " + path + ": " + std::strerror(errno);
    close(fd);
  }
  return "";
}

// How a command of a cell ended: state "" when it succeeded, else failed, killed or
// interrupted, with the cell's exit status and why.
struct StepEnd {
  std::string state;
  int exit_status = 0;
  std::string message;
};

// Runs `command` as a process of `program`, its output in `log`.out and `log`.err; a signal the
// cell receives meanwhile is passed on to it.
StepEnd RunStep(const std::string& program, const std::vector<std::string>& command,
                const std::string& log, bool in_slurm) {
  std::vector<std::string> argv = {program};
  argv.insert(argv.end(), command.begin(), command.end());
  // The logs are opened here first: posix_spawn's failure to open them reads as the
  // program's ("cannot start attend: No such file or directory").
  const std::string log_error = CheckWritable({log + ".out", log + ".err"});
  if (!log_error.empty()) return {"failed", 2, command[0] + " could not start: " + log_error};
  std::string start_error;
  const pid_t pid = StartProcess(argv, log + ".out", log + ".err", &start_error, true);
  if (pid < 0) return {"failed", 1, "cannot start " + program + ": " + start_error};
  g_command_pid.store(pid);
  // A signal that came before the pid was known still reaches the command.
  if (g_cell_signal.load() != 0) kill(pid, g_cell_signal.load());
  const ProcessExit exit = WaitProcess(pid);
  g_command_pid.store(0);
  const int signal = g_cell_signal.load();
  if (exit.Status() == 0 && signal == 0) return {};
  if (signal != 0) {
    const std::string cause = std::string(strsignal(signal)) + " during " + command[0];
    return in_slurm
               ? StepEnd{"killed", 128 + signal,
                         "stopped by Slurm (" + cause + "): a time limit, scancel or preemption"}
               : StepEnd{"interrupted", 128 + signal, cause};
  }
  if (exit.signal != 0) {
    return {"killed", exit.Status(), command[0] + " was killed by " + strsignal(exit.signal)};
  }
  const std::string error = ErrorMessage(ReadFileText(log + ".err"));
  return {"failed", exit.code,
          command[0] + (error.empty() ? " failed with exit status " + std::to_string(exit.code)
                                      : ": " + error)};
}

}  // namespace

int RunCell(const std::string& dir, int index) {
  const StoredSweep sweep = LoadSweepFolder(dir);
  if (index < 0 || index >= static_cast<int>(sweep.cells.size())) {
    throw ConfigError("--cell " + std::to_string(index) + ": " + dir + " has cells 0 to " +
                      std::to_string(sweep.cells.size() - 1));
  }
  const StoredCell& cell = sweep.cells[index];
  const fs::path cell_dir = sweep.CellDir(cell);
  std::error_code error;
  if (!fs::exists(cell_dir / "cell.json", error)) {
    throw InputError(cell_dir.string() + ": the cell's folder (or its cell.json) is missing; "
                     "attend sweep " + sweep.dir + " writes it again and runs the cell");
  }
  // One runner a cell: a second `--cell` (or a sweep that reaches the cell) is refused while
  // this one holds it; the lock of a runner that was killed is taken over.
  FolderLock lock(cell_dir.string(), "sweep cell");
  const std::vector<std::vector<std::string>> commands = ReadCellCommands(sweep, cell);
  fs::create_directories(cell_dir / "logs", error);
  if (error) {
    throw OutputError((cell_dir / "logs").string() + ": cannot create the folder: " +
                      error.message());
  }
  fs::remove(cell_dir / "scores.json", error);

  const char* job = std::getenv("SLURM_ARRAY_JOB_ID");
  const char* task = std::getenv("SLURM_ARRAY_TASK_ID");
  const bool in_slurm = job != nullptr && task != nullptr;
  Json running = {{"state", "running"},       {"cell", cell.name},
                  {"index", index},           {"executor", in_slurm ? "slurm" : "local"},
                  {"host", HostName()},       {"pid", static_cast<long>(getpid())},
                  {"started", UtcTimestamp()}};
  if (in_slurm) running["slurm_task"] = std::string(job) + "_" + task;
  if (!lock.stale_holder().empty()) running["took_over_lock_of"] = lock.stale_holder();
  CellStatusFile status(cell_dir, std::move(running));

  g_cell_signal.store(0);
  std::signal(SIGINT, OnCellSignal);
  std::signal(SIGTERM, OnCellSignal);
  const std::string program = SelfExecutable();
  std::string scorer_out;
  for (std::size_t step = 0; step < commands.size(); ++step) {
    if (g_cell_signal.load() != 0) break;
    const std::string log =
        (cell_dir / "logs" / (std::to_string(step + 1) + "-" + commands[step][0])).string();
    const StepEnd end = RunStep(program, commands[step], log, in_slurm);
    if (Vanished(cell_dir)) {
      return status.Finish("failed", 2, kVanished + (end.state.empty() ? std::string()
                                                                        : " (" + end.message + ")"));
    }
    if (!end.state.empty()) return status.Finish(end.state, end.exit_status, end.message);
    if (step + 1 == commands.size()) scorer_out = ReadFileText(log + ".out");
  }
  if (g_cell_signal.load() != 0) {
    const int signal = g_cell_signal.load();
    return status.Finish(in_slurm ? "killed" : "interrupted", 128 + signal, strsignal(signal));
  }
  Json scores;
  try {
    scores = CellScores(sweep.command, cell_dir, scorer_out);
  } catch (const std::exception& e) {
    return status.Finish("failed", 1, std::string("the scores cannot be read: ") + e.what());
  }
  try {
    ReplaceFileText((cell_dir / "scores.json").string(), JsonText(scores, 2) + "\n",
                    "the cell's scores");
  } catch (const Error& e) {
    return status.Finish("failed", 2, Vanished(cell_dir) ? kVanished : e.what());
  }
  return status.Finish("done", 0, "");
}

namespace {

std::string CellLine(const StoredSweep& sweep, int index) {
  return "cell " + std::to_string(index) + " (" + sweep.cells[index].name + ")";
}

// Starts `attend sweep DIR --cell I`; -1 when the cell is left to another process that runs
// it (skipped) or cannot start (failed), which `result` then counts and says why.
pid_t StartCell(const StoredSweep& sweep, int index, const std::string& program,
                LocalSweepResult* result) {
  const fs::path cell_dir = sweep.CellDir(sweep.cells[index]);
  // A cell that another process runs (`attend sweep DIR --cell I`, a Slurm task) is left to it.
  const std::string holder = FolderLockHolder(cell_dir.string());
  if (!holder.empty()) {
    ++result->progress.skipped;
    result->problems.push_back(CellLine(sweep, index) + ": running elsewhere (" + holder +
                               "); left to it");
    return -1;
  }
  const fs::path logs = cell_dir / "logs";
  std::error_code error;
  fs::create_directories(logs, error);
  // A cell folder that cannot be written fails alone; the others run.
  std::string problem = error ? logs.string() + ": cannot create the folder: " + error.message()
                              : CheckWritable({(logs / "cell.out").string(),
                                               (logs / "cell.err").string()});
  pid_t pid = -1;
  if (problem.empty()) {
    std::string start_error;
    pid = StartProcess({program, "sweep", sweep.dir, "--cell", std::to_string(index)},
                       (logs / "cell.out").string(), (logs / "cell.err").string(), &start_error,
                       true);
    if (pid < 0) problem = "cannot start " + start_error;
  }
  if (pid < 0) {
    ++result->progress.failed;
    result->problems.push_back(CellLine(sweep, index) + ": " + problem);
  }
  return pid;
}

// Counts cell `index`, whose process `pid` ended with `wait_status`. The record is the
// process's when it names its pid; else the cell ended before writing one (its folder cannot
// be written, its lock is held, the disk is full): its error says why.
void CountEnded(const StoredSweep& sweep, int index, pid_t pid, int wait_status, bool stopped,
                LocalSweepResult* result) {
  LocalProgress& progress = result->progress;
  CellStatus cell;
  std::string unreadable;
  try {
    cell = ReadCellStatus(sweep, sweep.cells[index]);
  } catch (const Error& e) {
    unreadable = e.what();
  }
  if (unreadable.empty() && cell.pid == pid && cell.state != CellState::kRunning) {
    if (cell.state == CellState::kDone) {
      ++progress.done;
      progress.cell_seconds += cell.seconds;
    } else if (cell.state == CellState::kFailed || cell.state == CellState::kKilled) {
      ++progress.failed;
      progress.cell_seconds += cell.seconds;
    }
    return;
  }
  const fs::path cell_dir = sweep.CellDir(sweep.cells[index]);
  std::string why = ErrorMessage(ReadFileText(cell_dir / "logs" / "cell.err"));
  if (why.empty()) why = unreadable;
  if (why.empty()) {
    const std::string cause = WhyUnwritable(cell_dir.string());
    why = (WIFEXITED(wait_status)
               ? "ended with exit status " + std::to_string(WEXITSTATUS(wait_status))
               : std::string("ended")) +
          " without a record" + (cause.empty() ? "" : " (" + cause + ")");
  }
  if (why.find("in use by another attend") != std::string::npos) {
    ++progress.skipped;
    result->problems.push_back(CellLine(sweep, index) + ": running elsewhere: " + why);
  } else if (!stopped) {
    ++progress.failed;
    result->problems.push_back(CellLine(sweep, index) + ": " + why);
  }
}

}  // namespace

LocalSweepResult RunSweepLocally(const StoredSweep& sweep, const std::vector<int>& indexes,
                                 int jobs, const std::atomic<int>* stop,
                                 const std::function<void(const LocalProgress&)>& on_progress) {
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
      const pid_t pid = StartCell(sweep, index, program, &result);
      if (pid > 0) running[pid] = index;
    }
    progress.running = static_cast<int>(running.size());
    progress.elapsed_s = watch.ElapsedMs() / 1000.0;
    if (on_progress) on_progress(progress);
    if (running.empty()) break;
    // Polled, so that a stop signal is passed on at once whatever the cells are doing.
    int wait_status = 0;
    const pid_t pid = waitpid(-1, &wait_status, WNOHANG);
    if (pid <= 0) {
      usleep(50000);
      continue;
    }
    const auto found = running.find(pid);
    if (found == running.end()) continue;
    const int index = found->second;
    running.erase(found);
    CountEnded(sweep, index, pid, wait_status, forwarded != 0, &result);
  }
  progress.running = 0;
  progress.elapsed_s = watch.ElapsedMs() / 1000.0;
  if (on_progress) on_progress(progress);
  return result;
}

}  // namespace attend
