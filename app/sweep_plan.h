// The sweep file of `attend sweep` (docs/SWEEPS.md): a base configuration, parameters as a grid
// and as zipped lists, the inputs with their ground truth and what to score, planned as cells
// (one configuration, one input), each with the attend commands that compute and score it.
//
// Planning is three steps, each a function below, run in order by PlanSweep:
//   1. ReadSweepFile: the file's sections, typed and checked on their own (known keys, lists,
//      each key given once, inputs that exist and suit the command);
//   2. CheckSweepSettings: every fixed set, swept value and combination against the
//      configuration (a key it does not have, a value out of range);
//   3. ExpandCells: the grid's combinations times the zips' steps, times the inputs.
// Everything is checked before any cell runs; an error is a ConfigError naming the sweep file's
// line. Nothing is written: scene inputs are rendered when the sweep folder is prepared
// (PrepareSweepFolder, app/sweep_folder.h).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "app/sweep_inputs.h"
#include "util/option_fields.h"

namespace attend {

// One value of a swept key: YAML text in flow style, as `--set KEY=VALUE` takes it.
using SweepSetting = std::pair<std::string, std::string>;

// A swept key's list of values (a grid's, or one of a zip group's), as written.
struct SweptList {
  std::string key;
  std::vector<std::string> values;  // flow text, as SweepSetting's
  std::vector<std::string> where;   // "FILE:LINE" of each value
};

struct SweepCell {
  int index = 0;  // stable within a sweep folder (cells added by --extend come after)
  std::string name;
  int input = 0;  // into SweepPlan::inputs
  std::vector<SweepSetting> settings;  // the swept keys' values, in SweepPlan::keys order
  int configuration = 0;  // into SweepConfigurations (and ConfigurationYamls)
};

// The most cells a sweep may have (docs/LIMITS.md). A cell is a folder of its own, a process
// (two: the command and its scorer) and, in Slurm, an array task: 10,000 cells of a second
// each are three hours of a whole machine here, and more than Slurm's default MaxArraySize
// (1001) tenfold; a study larger than that is several sweeps, or a coarser grid first.
inline constexpr long kMaxSweepCells = 10000;

// The sweep file's `slurm:` section: defaults of --partition, --time, --mem, --cpus-per-task
// and --throttle.
struct SlurmSettings {
  std::string partition;  // "" the cluster's default
  std::string time;       // sbatch --time, "" the partition's default
  std::string mem;        // sbatch --mem, "" the default
  int cpus_per_task = 1;
  int throttle = 0;  // at most this many array tasks at once (%M); 0 no limit

  static const OptionFields<SlurmSettings>& Fields();
};

// The options of eval-fixations in a sweep file's `score: {eval-fixations: ...}`.
struct FixationScoring {
  double sigma = 0.0;
  int max_side = 640;
  std::vector<std::string> baselines;
  double baseline_blur = 0.03;

  static const OptionFields<FixationScoring>& Fields();
};

struct SweepPlan {
  std::string file;  // the sweep file, absolute
  std::string text;  // its content
  SweepCommand command = SweepCommand::kRun;
  std::string config;             // the base configuration file, absolute ("" for track)
  std::vector<std::string> sets;  // fixed KEY=VALUE overrides of every cell
  std::string sets_where;         // "FILE:LINE" of `set:` ("" when the file has none)
  std::vector<SweptList> grid;
  std::vector<std::vector<SweptList>> zips;  // each zip group's lists, of one length
  std::vector<std::string> keys;  // the swept keys: the grid's, then each zip group's
  std::vector<std::vector<int>> groups;  // keys swept together: each grid key alone, each zip
  std::vector<SweepInput> inputs;
  FixationScoring fixations;  // options of eval-fixations
  SlurmSettings slurm;
  std::vector<SweepCell> cells;  // SweepConfigurations outermost, then the inputs
};

struct SweepReadOptions {
  // Read in place of the file's content (a sweep folder's stored copy); relative paths are
  // still resolved from the file's folder.
  const std::string* text = nullptr;
  // The sweep folder: scene inputs render into DIR/scenes/<name>-<hash of the scene file>.
  std::string dir;
};

// Step 1: reads the sweep file (no cells yet).
SweepPlan ReadSweepFile(const std::string& path, const SweepReadOptions& options = {});

// Step 2: checks the fixed sets, then each swept value on its own over them (an error names
// the value's line), then each combination (a value can be valid alone and not beside another).
void CheckSweepSettings(const SweepPlan& plan);

// The configurations: the grid's combinations (last key fastest) times each zip group's steps.
std::vector<std::vector<SweepSetting>> SweepConfigurations(const SweepPlan& plan);

// Step 3: the cells, configurations outermost, then the inputs.
std::vector<SweepCell> ExpandCells(const SweepPlan& plan);

// Steps 1 to 3: a sweep file read, checked and expanded into its cells.
SweepPlan PlanSweep(const std::string& path, const SweepReadOptions& options = {});

// The effective configuration of each configuration (SweepCell::configuration) as YAML, every
// key included: CellConfigYaml for all of them, the base file read once.
std::vector<std::string> ConfigurationYamls(const SweepPlan& plan);

// The effective configuration of a cell as YAML (every key, defaults included).
std::string CellConfigYaml(const SweepPlan& plan, const SweepCell& cell);

// The `--set KEY=VALUE` words of a cell: the fixed sets, then its settings.
std::vector<std::string> CellSets(const SweepPlan& plan, const SweepCell& cell);

// A cell's commands, without the program: the one that computes it and the one that scores
// it, writing below `cell_dir` (out/ the command's output).
std::vector<std::vector<std::string>> CellCommands(const SweepPlan& plan, const SweepCell& cell,
                                                   const std::string& cell_dir);

}  // namespace attend
