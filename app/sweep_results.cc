#include "app/sweep_results.h"

#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "app/sweep_records.h"
#include "app/sweep_slurm.h"
#include "eval/sweep_report.h"
#include "util/error.h"
#include "util/folder_lock.h"
#include "util/output_folder.h"
#include "util/strings.h"
#include "util/subprocess.h"

namespace attend {

namespace {

namespace fs = std::filesystem;

// A CSV field, quoted when it holds a comma, a quote or a line break (RFC 4180).
std::string CsvField(const std::string& text) {
  if (text.find_first_of(",\"\n\r") == std::string::npos) return text;
  std::string out = "\"";
  for (const char c : text) {
    out += c;
    if (c == '"') out += '"';
  }
  return out + "\"";
}

std::string CsvNumber(double value) {
  if (!std::isfinite(value)) return "";
  std::ostringstream text;
  text.precision(10);
  text << value;
  return text.str();
}

// Reads the cell's status.json and, done, its scores.json into `view`. A record that cannot
// be read (edited by hand, cut short) is no result: the cell is waiting, to run again, and
// the message naming the file and the key is returned.
std::string ReadRecords(const StoredSweep& sweep, const StoredCell& cell, CellView* view) {
  try {
    view->status = ReadCellStatus(sweep, cell);
    if (view->status.state == CellState::kDone) view->scores = ReadCellScores(sweep, cell);
  } catch (const Error& e) {
    view->status = CellStatus();
    view->scores.clear();
    return std::string(e.what()) + "; the cell runs again";
  }
  return "";
}

// A folder that cannot be written fails whatever runs it; a done cell keeps its result.
void CheckWritable(const std::string& cell_dir, CellView* view) {
  std::error_code error;
  if (view->state != CellState::kDone && view->state != CellState::kRunning &&
      fs::is_directory(cell_dir, error) && access(cell_dir.c_str(), W_OK) != 0) {
    view->state = CellState::kFailed;
    view->unwritable = true;
    view->detail = cell_dir + ": cannot be written (" + std::strerror(errno) +
                   "); make it writable, and it runs again";
  }
}

}  // namespace

std::vector<CellView> ViewCells(const StoredSweep& sweep, std::vector<std::string>* notes) {
  const SlurmView slurm = QuerySlurm(sweep);
  if (slurm.has_jobs && !slurm.note.empty()) notes->push_back(slurm.note);
  const std::string host = HostName();
  std::vector<CellView> views;
  for (const StoredCell& cell : sweep.cells) {
    CellView view;
    view.index = cell.index;
    const std::string cell_dir = sweep.CellDir(cell);
    const std::string damaged = ReadRecords(sweep, cell, &view);
    // Whoever holds the cell's lock runs it, whatever its record says.
    const std::string holder = FolderLockHolder(cell_dir);
    const auto queued = slurm.queued.find(cell.index);
    view.queued = queued != slurm.queued.end();
    const std::string slurm_state = view.queued ? queued->second : "";
    const CellStatus& status = view.status;
    if (!holder.empty()) {
      view.state = CellState::kRunning;
      view.detail = holder;
      views.push_back(std::move(view));
      continue;
    }
    if (!damaged.empty()) notes->push_back("cell " + std::to_string(cell.index) + ": " + damaged);
    switch (status.state) {
      case CellState::kDone:
        view.state = CellState::kDone;
        break;
      case CellState::kFailed:
        view.state = CellState::kFailed;
        view.detail = "exit status " + std::to_string(status.exit_status) + ": " + status.message;
        break;
      case CellState::kKilled: {
        view.state = CellState::kKilled;
        view.detail = status.message;
        // Slurm's word: the task's state while it still holds it (COMPLETING), else its end.
        const std::string final_state =
            status.slurm_task.empty() ? ""
            : view.queued             ? slurm_state
                                      : SlurmFinalState(status.slurm_task);
        if (!final_state.empty()) view.detail += " (Slurm: " + final_state + ")";
        break;
      }
      case CellState::kRunning:
        if (status.executor == "slurm") {
          if (view.queued) {
            view.state = CellState::kRunning;
            view.detail = "Slurm task " + status.slurm_task + ": " + slurm_state;
          } else {
            // Gone without a record: killed past its KillWait, or its node failed.
            view.state = CellState::kKilled;
            const std::string final_state = SlurmFinalState(status.slurm_task);
            view.detail = "Slurm task " + status.slurm_task + " ended without a record" +
                          (final_state.empty() ? std::string(" (its state is no longer known)")
                                               : " (Slurm: " + final_state + ")");
          }
        } else if (status.host == host && ProcessAlive(static_cast<pid_t>(status.pid))) {
          view.state = CellState::kRunning;
          view.detail = "pid " + std::to_string(status.pid);
        } else {
          view.state = CellState::kWaiting;
          view.detail = "was running (pid " + std::to_string(status.pid) + " on " + status.host +
                        ") and ended without a record; it runs again";
        }
        break;
      case CellState::kInterrupted:
      case CellState::kWaiting:
        view.state = CellState::kWaiting;
        if (status.state == CellState::kInterrupted) view.detail = "interrupted: " + status.message;
        if (!damaged.empty()) view.detail = damaged;
        if (view.queued) {
          view.state = slurm_state == "PENDING" ? CellState::kWaiting : CellState::kRunning;
          view.detail = "Slurm task " + slurm.task.at(cell.index) + ": " + slurm_state;
        }
        break;
    }
    CheckWritable(cell_dir, &view);
    views.push_back(std::move(view));
  }
  return views;
}

std::vector<int> CellsToRun(const std::vector<CellView>& cells, bool retry_failed) {
  std::vector<int> indexes;
  for (const CellView& cell : cells) {
    if (cell.queued) continue;
    const bool failed = cell.state == CellState::kFailed || cell.state == CellState::kKilled;
    // An unwritable folder is no recorded failure: each run tries the cell, which fails (and
    // is counted) again until the folder can be written.
    if (cell.unwritable || (retry_failed ? failed : cell.state == CellState::kWaiting)) {
      indexes.push_back(cell.index);
    }
  }
  return indexes;
}

std::string StatusText(const StoredSweep& sweep, const std::vector<CellView>& cells) {
  std::map<CellState, int> counts;
  for (const CellView& cell : cells) ++counts[cell.state];
  std::ostringstream text;
  text << sweep.dir << ": " << cells.size() << " cells: " << counts[CellState::kDone] << " done, "
       << counts[CellState::kRunning] << " running, " << counts[CellState::kFailed]
       << " failed, " << counts[CellState::kKilled] << " killed, "
       << counts[CellState::kWaiting] << " waiting\n";
  std::size_t width = 4;
  for (const StoredCell& cell : sweep.cells) width = std::max(width, cell.name.size());
  for (const CellView& cell : cells) {
    const StoredCell& stored = sweep.cells[cell.index];
    std::string line = std::to_string(cell.index);
    line.resize(5, ' ');
    std::string name = stored.name;
    name.resize(width + 2, ' ');
    std::string state = CellStateName(cell.state);
    state.resize(9, ' ');
    line += name + state;
    if (cell.state == CellState::kDone) line += Fixed(cell.status.seconds, 1) + " s";
    if (!cell.detail.empty()) line += (cell.state == CellState::kDone ? "  " : "") + cell.detail;
    while (!line.empty() && line.back() == ' ') line.pop_back();
    text << line << "\n";
  }
  return text.str();
}

CollectResult CollectSweep(const StoredSweep& sweep, const std::string& command_line) {
  CollectResult result;
  SweepReportInput report;
  report.dir = sweep.dir;
  report.command = sweep.command;
  report.command_line = command_line;
  report.keys = sweep.keys;
  report.groups = sweep.groups;
  const std::vector<CellView> views = ViewCells(sweep, &report.notes);
  std::vector<std::vector<std::pair<std::string, double>>> all_scores;
  for (const CellView& view : views) {
    const StoredCell& stored = sweep.cells[view.index];
    SweepReportCell cell;
    cell.name = stored.name;
    cell.input = stored.input;
    for (const auto& [key, value] : stored.settings) cell.settings.push_back(value);
    cell.state = CellStateName(view.state);
    cell.message = view.detail;
    cell.seconds = view.status.seconds;
    for (const auto& [name, value] : view.scores) {
      cell.scores[name] = value;
      if (std::find(report.scores.begin(), report.scores.end(), name) == report.scores.end()) {
        report.scores.push_back(name);
      }
    }
    const fs::path cell_dir = sweep.CellDir(stored);
    cell.config_yaml = ReadFileText(cell_dir / "config.yaml");
    // The settings of the best configurations; a cell.json that is missing or damaged only
    // leaves them out (the cell itself is waiting: a run writes the file again).
    std::error_code error;
    if (fs::exists(cell_dir / "cell.json", error)) {
      try {
        const SweepRecord description = SweepRecord::Load((cell_dir / "cell.json").string());
        cell.sets = description.Strings("sets");
        cell.config = description.String("config");
      } catch (const Error& e) {
        report.notes.push_back(std::string(e.what()) + "; remove the folder " +
                               cell_dir.string() + " to run the cell again");
      }
    }
    result.done += view.state == CellState::kDone ? 1 : 0;
    report.cells.push_back(std::move(cell));
  }
  result.cells = static_cast<int>(report.cells.size());

  std::string csv = "cell,input";
  for (const std::string& key : report.keys) csv += "," + CsvField(key);
  csv += ",state,exit_status,seconds";
  for (const std::string& score : report.scores) csv += "," + CsvField(score);
  csv += "\n";
  for (std::size_t i = 0; i < report.cells.size(); ++i) {
    const SweepReportCell& cell = report.cells[i];
    csv += CsvField(cell.name) + "," + CsvField(cell.input);
    for (const std::string& value : cell.settings) csv += "," + CsvField(value);
    const CellStatus& status = views[i].status;
    const bool finished = views[i].state == CellState::kDone ||
                          views[i].state == CellState::kFailed ||
                          views[i].state == CellState::kKilled;
    csv += "," + cell.state + "," + (finished ? std::to_string(status.exit_status) : "") + "," +
           (finished ? CsvNumber(status.seconds) : "");
    for (const std::string& score : report.scores) {
      const auto found = cell.scores.find(score);
      csv += "," + (found == cell.scores.end() ? "" : CsvNumber(found->second));
    }
    csv += "\n";
  }
  report.chart = LoadChartLibrary();
  result.csv = (fs::path(sweep.dir) / "sweep.csv").string();
  result.html = (fs::path(sweep.dir) / "report.html").string();
  ReplaceFileText(result.csv, csv, "the sweep's scores");
  ReplaceFileText(result.html, SweepReportHtml(report), "the sweep's report");
  result.notes = report.notes;
  return result;
}

}  // namespace attend
