// The controller of `attend sweep` (docs/SWEEPS.md): a sweep file planned (or a sweep folder's
// copy of it, to run again where it stopped), its cells listed without running (a dry run),
// run on this machine or submitted to Slurm as a job array; and a sweep folder's status. The
// command only parses its arguments and prints what comes back; the cells themselves are
// app/sweep_cell.h's, the folder app/sweep_folder.h's, --collect app/sweep_results.h's.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "app/sweep_cell.h"
#include "app/sweep_plan.h"
#include "app/sweep_slurm.h"

namespace attend {

// The command line's Slurm settings, each over the sweep file's `slurm:` when given.
struct SlurmOverrides {
  std::optional<std::string> partition;
  std::optional<std::string> time;
  std::optional<std::string> mem;
  std::optional<int> cpus_per_task;
  std::optional<int> throttle;
};

struct SweepRequest {
  std::string target;  // a sweep file, or a sweep folder (run again in place)
  std::string out;     // the sweep folder of a sweep file
  bool dry_run = false;
  bool extend = false;        // add the cells a changed sweep file has beyond the folder's
  bool retry_failed = false;  // run only the failed and killed cells
  bool slurm = false;         // submit a job array; else run here
  int local = 0;              // cells at once here; 0: the cores
  SlurmOverrides slurm_overrides;
  std::string command_line;  // recorded in the batch script
};

// Whether `path` is a sweep folder (holds sweep.json).
bool IsSweepFolder(const std::string& path);

// ConfigError naming `mode` (--status, --collect, --cell) when `target` is not a sweep folder.
void RequireSweepFolder(const std::string& target, const std::string& mode);

// A request's sweep, planned: the sweep file's cells, the folder they go to and the Slurm
// settings (the file's, with the command line's over them).
struct OpenedSweep {
  SweepPlan plan;
  std::string out;  // "" only in a dry run without --out
  SlurmSettings slurm;
};

// Plans the request's sweep file, or the copy of it in the sweep folder it names. ConfigError
// for a bad sweep file, a missing --out or an --out beside a sweep folder; OutputError for an
// --out that is neither new nor a sweep folder. Writes nothing.
OpenedSweep OpenSweep(const SweepRequest& request);

// What a dry run prints: the cells, then each cell's commands or, with --slurm, the batch
// script.
std::string DryRunText(const SweepRequest& request, const OpenedSweep& sweep);

// The --status text of a sweep folder, and why Slurm could not be asked (notes).
struct SweepStatus {
  std::string text;
  std::vector<std::string> notes;
};
SweepStatus ReadSweepStatus(const std::string& dir);

// What a sweep tells while it runs.
struct SweepObserver {
  std::function<void(const std::string&)> on_note;        // what the folder kept or added, ...
  std::function<void(const LocalProgress&)> on_progress;  // a local run's progress
};

struct SweepRunResult {
  std::string dir;           // the sweep folder
  std::vector<int> started;  // the cells run or submitted; empty: nothing to run
  // The folder's cells before the run.
  int cells = 0;
  int done = 0;
  int failed = 0;                             // failed or killed
  int queued = 0;                             // still queued in Slurm
  int running = 0;                            // run by another process (their locks held)
  std::optional<SlurmSubmission> submission;  // with --slurm
  int jobs = 0;                               // cells at once, run here
  LocalSweepResult local;                     // run here
};

// Prepares the sweep folder (app/sweep_folder.h) and runs the cells without a result (with
// `retry_failed`, the failed and killed ones): here, `jobs` at once until done or a SIGINT or
// SIGTERM stops them, or submitted to Slurm.
SweepRunResult RunSweep(const SweepRequest& request, const OpenedSweep& sweep,
                        const SweepObserver& observer);

}  // namespace attend
