#include "app/run_sweep.h"

#include <algorithm>
#include <atomic>
#include <csignal>
#include <filesystem>
#include <thread>

#include "app/sweep_folder.h"
#include "app/sweep_results.h"
#include "util/error.h"
#include "util/folder_lock.h"
#include "util/output_folder.h"
#include "util/strings.h"
#include "util/subprocess.h"

namespace attend {

namespace {

namespace fs = std::filesystem;

// The signal that stops a local sweep; a signal handler can only reach globals.
std::atomic<int> g_sweep_signal{0};

extern "C" void OnSweepSignal(int signal) {
  g_sweep_signal.store(signal);
  std::signal(signal, SIG_DFL);  // a second one stops at once
}

std::string SettingsLine(const std::vector<SweepSetting>& settings) {
  std::vector<std::string> parts;
  for (const auto& [key, value] : settings) parts.push_back(key + "=" + value);
  return parts.empty() ? "(base)" : Join(parts, " ");
}

SlurmSettings WithOverrides(SlurmSettings slurm, const SlurmOverrides& overrides) {
  if (overrides.partition) slurm.partition = *overrides.partition;
  if (overrides.time) slurm.time = *overrides.time;
  if (overrides.mem) slurm.mem = *overrides.mem;
  if (overrides.cpus_per_task) slurm.cpus_per_task = *overrides.cpus_per_task;
  if (overrides.throttle) slurm.throttle = *overrides.throttle;
  return slurm;
}

// The sweep file kept in a sweep folder, planned again.
OpenedSweep OpenSweepFolder(const SweepRequest& request) {
  const StoredSweep stored = LoadSweepFolder(request.target);
  if (!request.out.empty() &&
      fs::weakly_canonical(request.out) != fs::weakly_canonical(request.target)) {
    throw ConfigError("--out " + request.out +
                      ": a sweep folder is run again in place; leave --out out");
  }
  OpenedSweep opened;
  opened.out = request.target;
  const std::string copy = ReadFileText((fs::path(request.target) / "sweep.yaml").string());
  SweepReadOptions options;
  options.text = &copy;
  options.dir = opened.out;
  opened.plan = PlanSweep(stored.file, options);
  return opened;
}

// A sweep file, planned for the folder --out.
OpenedSweep OpenSweepFile(const SweepRequest& request) {
  std::error_code error;
  if (fs::is_directory(request.target, error)) {
    throw ConfigError(request.target +
                      ": a folder without sweep.json; give a sweep file (YAML) "
                      "or a sweep folder");
  }
  const std::string& out = request.out;
  if (out.empty() && !request.dry_run) throw ConfigError("--out is required with a sweep file");
  if (!out.empty() && !request.dry_run && !IsSweepFolder(out) && !IsEmptyOrScenesOnly(out)) {
    throw OutputError(out +
                      ": not empty and not a sweep folder (no sweep.json); give a new "
                      "--out");
  }
  OpenedSweep opened;
  opened.out = out;
  SweepReadOptions options;
  options.dir = out;
  opened.plan = PlanSweep(request.target, options);
  return opened;
}

// Runs `indexes` here, stopped early by SIGINT or SIGTERM.
LocalSweepResult RunHere(const StoredSweep& sweep, const std::vector<int>& indexes, int jobs,
                         const SweepObserver& observer) {
  g_sweep_signal.store(0);
  std::signal(SIGINT, OnSweepSignal);
  std::signal(SIGTERM, OnSweepSignal);
  return RunSweepLocally(sweep, indexes, jobs, &g_sweep_signal, [&](const LocalProgress& progress) {
    if (observer.on_progress) observer.on_progress(progress);
  });
}

}  // namespace

bool IsSweepFolder(const std::string& path) {
  std::error_code error;
  return fs::is_regular_file(fs::path(path) / "sweep.json", error);
}

void RequireSweepFolder(const std::string& target, const std::string& mode) {
  if (!IsSweepFolder(target)) {
    throw ConfigError(mode + " takes a sweep folder (one holding sweep.json); " + target +
                      " is not one");
  }
}

OpenedSweep OpenSweep(const SweepRequest& request) {
  OpenedSweep opened =
      IsSweepFolder(request.target) ? OpenSweepFolder(request) : OpenSweepFile(request);
  opened.slurm = WithOverrides(opened.plan.slurm, request.slurm_overrides);
  return opened;
}

std::string DryRunText(const SweepRequest& request, const OpenedSweep& opened) {
  const SweepPlan& plan = opened.plan;
  const std::string dir =
      fs::absolute(opened.out.empty() ? "SWEEP_DIR" : opened.out).lexically_normal();
  std::string text = std::to_string(plan.cells.size()) + " cells of attend " +
                     SweepCommandName(plan.command) + " (" + std::to_string(plan.inputs.size()) +
                     " inputs):\n";
  std::vector<int> indexes;
  for (const SweepCell& cell : plan.cells) {
    text += std::to_string(cell.index) + "  " + cell.name + "  " + plan.inputs[cell.input].name +
            "  " + SettingsLine(cell.settings) + "\n";
    indexes.push_back(cell.index);
  }
  if (request.slurm) {
    StoredSweep sweep;
    sweep.dir = dir;
    return text + "\nThe batch script:\n" +
           SlurmBatchScript(sweep, indexes, opened.slurm, SelfExecutable(), request.command_line);
  }
  text += "\nThe commands of each cell:\n";
  for (const SweepCell& cell : plan.cells) {
    const std::string cell_dir = (fs::path(dir) / "cells" / cell.name).string();
    for (std::vector<std::string> command : CellCommands(plan, cell, cell_dir)) {
      command.insert(command.begin(), "attend");
      text += ShellQuote(command) + "\n";
    }
  }
  return text;
}

SweepStatus ReadSweepStatus(const std::string& dir) {
  const StoredSweep sweep = LoadSweepFolder(dir);
  SweepStatus status;
  const std::vector<CellView> cells = ViewCells(sweep, &status.notes);
  status.text = StatusText(sweep, cells);
  return status;
}

SweepRunResult RunSweep(const SweepRequest& request, const OpenedSweep& opened,
                        const SweepObserver& observer) {
  // One sweep at a time a folder, from before its preparation (a second, an --extend or a
  // --retry-failed is refused at once, writing nothing) to its last cell. A sweep that was
  // killed leaves a stale lock, taken over here.
  std::error_code error;
  fs::create_directories(opened.out, error);
  if (error) throw OutputError(opened.out + ": cannot create the folder: " + error.message());
  const FolderLock lock(opened.out, "sweep");
  std::vector<std::string> notes;
  if (!lock.stale_holder().empty()) {
    notes.push_back("took over the lock of a sweep that ended without releasing it (" +
                    lock.stale_holder() + ")");
  }
  const StoredSweep sweep = PrepareSweepFolder(opened.plan, opened.out, request.extend, &notes);
  const std::vector<CellView> cells = ViewCells(sweep, &notes);
  for (const std::string& note : notes) {
    if (observer.on_note) observer.on_note(note);
  }
  SweepRunResult result;
  result.dir = sweep.dir;
  result.started = CellsToRun(cells, request.retry_failed);
  result.cells = static_cast<int>(cells.size());
  for (const CellView& cell : cells) {
    result.done += cell.state == CellState::kDone ? 1 : 0;
    result.failed += cell.state == CellState::kFailed || cell.state == CellState::kKilled ? 1 : 0;
    result.queued += cell.queued ? 1 : 0;
    result.running += cell.state == CellState::kRunning && !cell.queued ? 1 : 0;
  }
  if (result.started.empty()) return result;
  if (request.slurm) {
    const std::string script = SlurmBatchScript(sweep, result.started, opened.slurm,
                                                SelfExecutable(), request.command_line);
    result.submission = SubmitSlurmArray(sweep, script);
    return result;
  }
  result.jobs = request.local > 0
                    ? request.local
                    : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  result.local = RunHere(sweep, result.started, result.jobs, observer);
  return result;
}

}  // namespace attend
