// The folder of a sweep (docs/SWEEPS.md) and the work of its cells:
//
//   DIR/sweep.yaml              the sweep file as last run (a copy)
//   DIR/sweep.json              the cells: index, name, input and settings
//   DIR/cells/NAME/cell.json    the cell: its settings, input, attend version and commands
//   DIR/cells/NAME/config.yaml  its effective configuration
//   DIR/cells/NAME/status.json  running, done, failed (exit status and message) or killed
//   DIR/cells/NAME/scores.json  its scores, once done
//   DIR/cells/NAME/logs/        each command's standard output and error
//   DIR/cells/NAME/out/         what its command wrote (the run folder of attend run)
//   DIR/slurm/                  batch scripts, jobs.json and the array tasks' logs
//   DIR/sweep.csv, report.html  written by --collect
//
// A cell is computed by `attend sweep DIR --cell INDEX` (app/sweep_cell.h).
#pragma once

#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "app/sweep_plan.h"
#include "app/sweep_records.h"

namespace attend {

struct StoredCell {
  int index = 0;
  std::string name;
  std::string input;
  std::vector<SweepSetting> settings;
};

struct StoredSweep {
  std::string dir;
  std::string file;     // the sweep file it was made from
  std::string command;  // run, track or saliency
  std::vector<std::string> keys;
  std::vector<std::vector<int>> groups;  // keys swept together (SweepPlan::groups)
  std::vector<StoredCell> cells;  // by index
  SlurmSettings slurm;
  std::string CellDir(const StoredCell& cell) const;
};

// Creates DIR for `plan`, or takes it again when it holds the same sweep (cells with the same
// names, commands and configurations). A sweep file that adds cells is refused unless `extend`
// (the new cells are appended, the old keep their indexes); one that changes what an existing
// cell runs is refused always. ConfigError for both; OutputError when DIR cannot be written or
// holds something else. Once the cells are accepted, the scene inputs not yet rendered are
// rendered into DIR/scenes/. `notes` receives what was kept or added.
StoredSweep PrepareSweepFolder(const SweepPlan& plan, const std::string& dir, bool extend,
                               std::vector<std::string>* notes);

// Whether `dir` can become a new sweep folder: missing, empty, or holding only what a
// preparation stopped before sweep.json leaves (scenes/, sweep.yaml, a lock file).
bool IsEmptyOrScenesOnly(const std::string& dir);

// Reads DIR/sweep.json. InputError when DIR is not a sweep folder.
StoredSweep LoadSweepFolder(const std::string& dir);

const char* CellStateName(CellState state);

// What DIR/cells/NAME/status.json says (kWaiting when there is none). InputError naming the
// file and the key when it is not a status record (app/sweep_records.h).
CellStatus ReadCellStatus(const StoredSweep& sweep, const StoredCell& cell);

// The cell's scores (DIR/cells/NAME/scores.json), name to value, in the scorer's order.
// InputError when the file is missing or holds anything but a map of numbers (and nulls).
std::vector<std::pair<std::string, double>> ReadCellScores(const StoredSweep& sweep,
                                                           const StoredCell& cell);

// The commands of a cell, as its cell.json lists them (what RunCell runs).
std::vector<std::vector<std::string>> ReadCellCommands(const StoredSweep& sweep,
                                                       const StoredCell& cell);

}  // namespace attend
