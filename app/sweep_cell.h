// The work of a sweep's cells (docs/SWEEPS.md): one cell computed and scored by `attend sweep
// DIR --cell INDEX`, whichever executor starts it (this machine or a Slurm array task), so both
// give the same results; and the local executor, which starts those processes N at a time.
#pragma once

#include <atomic>
#include <functional>
#include <string>
#include <vector>

#include "app/sweep_folder.h"

namespace attend {

// Computes and scores cell `index` of DIR: its commands one after the other, each a process
// of this program, recording status.json and scores.json. SIGINT and SIGTERM are passed on to
// the command running; the cell is then recorded as interrupted (or, in a Slurm job, killed).
// The cell folder is locked while the cell runs (util/folder_lock.h): OutputError while another
// process runs it. A cell folder removed while it runs is recorded as failed ("the cell folder
// vanished while it ran") in the folder made again. Returns the cell's exit status (0 done).
int RunCell(const std::string& dir, int index);

struct LocalProgress {
  int total = 0;
  int done = 0;
  int failed = 0;
  int running = 0;
  int skipped = 0;  // run by another process meanwhile (its lock held)
  double elapsed_s = 0.0;
  double cell_seconds = 0.0;  // sum of the finished cells' wall times
};

struct LocalSweepResult {
  LocalProgress progress;
  int stop_signal = 0;  // the signal that stopped the sweep early, 0 when it ran to the end
  // "cell I (NAME): why", for each cell that could not run or ended without its own record
  // (failed) and each left to another process that runs it (skipped).
  std::vector<std::string> problems;
};

// Runs `indexes` of DIR on this machine, `jobs` cells at once, each `attend sweep DIR --cell
// I`. `stop` ends it early: no new cell starts and the running ones receive the signal. The
// caller holds the sweep folder's lock (one sweep at a time a folder, app/run_sweep.h); a cell
// locked by another process (its own `--cell`, a Slurm task) is skipped, and a cell whose
// folder cannot be written fails alone.
LocalSweepResult RunSweepLocally(const StoredSweep& sweep, const std::vector<int>& indexes,
                                 int jobs, const std::atomic<int>* stop,
                                 const std::function<void(const LocalProgress&)>& on_progress);

}  // namespace attend
