// What a sweep's cells are doing (`attend sweep DIR --status`), which cells a run starts, and
// the collection of their scores into DIR/sweep.csv and DIR/report.html (`--collect`).
#pragma once

#include <string>
#include <vector>

#include "app/sweep_folder.h"

namespace attend {

// A cell as the run folders and Slurm together see it.
struct CellView {
  int index = 0;
  CellStatus status;  // what status.json says
  CellState state = CellState::kWaiting;  // running only when its process or task is alive
  std::string detail;  // a failed cell's message, Slurm's word on a queued or killed one
  bool queued = false;  // Slurm still holds its array task (pending or running)
  std::vector<std::pair<std::string, double>> scores;  // a done cell's
  bool unwritable = false;  // failed: its folder cannot be written (nothing records that)
};

// The cells of `sweep`; Slurm is asked (squeue, then sacct or scontrol) when the sweep was
// submitted there. A cell whose lock is held is running. A cell whose status.json or (done)
// scores.json cannot be read is waiting, to run again, and `notes` names the file and the key
// (docs/SWEEPS.md); they also receive why Slurm could not be asked. A cell folder that cannot
// be written is a failed cell.
std::vector<CellView> ViewCells(const StoredSweep& sweep, std::vector<std::string>* notes);

// The cells a run starts: those without a complete result and not queued in Slurm; with
// `retry_failed`, only the failed and killed ones. Cells whose folder cannot be written are
// started either way (and fail again, counted, until it can).
std::vector<int> CellsToRun(const std::vector<CellView>& cells, bool retry_failed);

// The --status text: one line of counts, then a line a cell.
std::string StatusText(const StoredSweep& sweep, const std::vector<CellView>& cells);

struct CollectResult {
  std::string csv;   // DIR/sweep.csv
  std::string html;  // DIR/report.html
  int cells = 0;
  int done = 0;
  std::vector<std::string> notes;
};

// Writes DIR/sweep.csv (a row a cell: name, input, the swept keys' values, state, exit status,
// seconds, then every score) and DIR/report.html.
CollectResult CollectSweep(const StoredSweep& sweep, const std::string& command_line);

}  // namespace attend
