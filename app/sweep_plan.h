// The sweep file of `attend sweep` (docs/SWEEPS.md): a base configuration, parameters as a grid
// and as zipped lists, the inputs with their ground truth and what to score, read into cells
// (one configuration, one input), each with the attend commands that compute and score it.
// Everything is checked here, before any cell runs: a key the configuration does not have, a
// value out of range, a missing input or an empty grid is a ConfigError naming the sweep
// file's line.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace attend {

// What each cell runs: `attend run` scored by `attend eval`, `attend track` scored by
// `attend eval-tracking`, or `attend saliency` scored by `attend eval-fixations`.
enum class SweepCommand { kRun, kTrack, kSaliency };

const char* SweepCommandName(SweepCommand command);

struct SweepInput {
  std::string name;  // unique among the inputs; part of the cells' folder names
  // sequence, video, images, left (with right), side_by_side, fixations, or scene (a scene
  // file rendered once into the sweep folder's scenes/, then a sequence)
  std::string kind;
  std::string path;   // absolute; for a scene, the sequence it renders into
  std::string scene;  // a scene's file
  std::string right;  // the right video of a left/right pair
  std::string gt;     // run: a gt/ folder; track: an OTB groundtruth_rect.txt; "" the default
  int gt_id = -1;     // unused today; kept for objects.csv with several objects
  std::string frames;  // FIRST:LAST, "" for all
  int skip = 0;        // fixations: leave out the first N images (by id) ...
  int first = 0;       // ... and take the next N (0: all)
  std::string where;   // "FILE:LINE" of its entry
};

// One value of a swept key: YAML text in flow style, as `--set KEY=VALUE` takes it.
using SweepSetting = std::pair<std::string, std::string>;

struct SweepCell {
  int index = 0;  // stable within a sweep folder (cells added by --extend come after)
  std::string name;
  int input = 0;  // into SweepPlan::inputs
  std::vector<SweepSetting> settings;  // the swept keys' values, in SweepPlan::keys order
};

struct SlurmSettings {
  std::string partition;  // "" the cluster's default
  std::string time;       // sbatch --time, "" the partition's default
  std::string mem;        // sbatch --mem, "" the default
  int cpus_per_task = 1;
  int throttle = 0;  // at most this many array tasks at once (%M); 0 no limit
};

struct FixationScoring {
  double sigma = 0.0;
  int max_side = 640;
  std::vector<std::string> baselines;
  double baseline_blur = 0.03;
};

struct SweepPlan {
  std::string file;  // the sweep file, absolute
  std::string text;  // its content
  SweepCommand command = SweepCommand::kRun;
  std::string config;             // the base configuration file, absolute ("" for track)
  std::vector<std::string> sets;  // fixed KEY=VALUE overrides of every cell
  std::vector<std::string> keys;  // the swept keys: the grid's, then each zip group's
  std::vector<std::vector<int>> groups;  // keys swept together: each grid key alone, each zip
  std::vector<SweepInput> inputs;
  FixationScoring fixations;  // options of eval-fixations
  SlurmSettings slurm;
  std::vector<SweepCell> cells;  // inputs outermost, then the grid (last key fastest), then zips
};

struct SweepReadOptions {
  // Read in place of the file's content (a sweep folder's stored copy); relative paths are
  // still resolved from the file's folder.
  const std::string* text = nullptr;
  // The sweep folder: scene inputs render into DIR/scenes/<name>-<hash of the scene file>.
  std::string dir;
  // Render the scenes not yet rendered, once everything else is checked.
  bool render = false;
};

// Reads and checks a sweep file.
SweepPlan ReadSweepFile(const std::string& path, const SweepReadOptions& options = {});

// The effective configuration of a cell as YAML (every key, defaults included).
std::string CellConfigYaml(const SweepPlan& plan, const SweepCell& cell);

// The `--set KEY=VALUE` words of a cell: the fixed sets, then its settings.
std::vector<std::string> CellSets(const SweepPlan& plan, const SweepCell& cell);

// A cell's commands, without the program: the one that computes it and the one that scores
// it, writing below `cell_dir` (out/ the command's output).
std::vector<std::vector<std::string>> CellCommands(const SweepPlan& plan, const SweepCell& cell,
                                                   const std::string& cell_dir);

}  // namespace attend
