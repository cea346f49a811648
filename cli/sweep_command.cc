// attend sweep: parameter studies over datasets, on this machine or as a Slurm job array, with
// one report (docs/SWEEPS.md).
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <thread>

#include "app/sweep_folder.h"
#include "app/sweep_plan.h"
#include "app/sweep_results.h"
#include "app/sweep_slurm.h"
#include "cli/commands.h"
#include "util/error.h"
#include "util/output_folder.h"
#include "util/strings.h"
#include "util/subprocess.h"
#include "util/timer.h"

namespace attend {

namespace {

namespace fs = std::filesystem;

std::atomic<int> g_sweep_signal{0};

extern "C" void OnSweepSignal(int signal) {
  g_sweep_signal.store(signal);
  std::signal(signal, SIG_DFL);  // a second one stops at once
}

struct SweepArguments {
  std::string target;
  std::string out;
  int local = 0;
  bool slurm = false;
  std::optional<std::string> partition;
  std::optional<std::string> time;
  std::optional<std::string> mem;
  std::optional<int> cpus_per_task;
  std::optional<int> throttle;
  bool status = false;
  bool collect = false;
  bool dry_run = false;
  bool extend = false;
  bool retry_failed = false;
  std::optional<int> cell;
  bool quiet = false;
  std::string command_line;
};

bool IsSweepFolder(const std::string& path) {
  std::error_code error;
  return fs::is_regular_file(fs::path(path) / "sweep.json", error);
}

void RequireFolder(const SweepArguments& args, const std::string& what) {
  if (!IsSweepFolder(args.target)) {
    throw ConfigError(what + " takes a sweep folder (one holding sweep.json); " + args.target +
                      " is not one");
  }
}

std::string SettingsLine(const std::vector<SweepSetting>& settings) {
  std::vector<std::string> parts;
  for (const auto& [key, value] : settings) parts.push_back(key + "=" + value);
  return parts.empty() ? "(base)" : Join(parts, " ");
}

void PrintProgress(const LocalProgress& p, bool tty) {
  static Stopwatch since_last;
  const int finished = p.done + p.failed;
  static int last_finished = -1;
  const bool last = finished == p.total && p.running == 0;
  if (tty) {
    if (!last && since_last.ElapsedMs() < 250.0) return;
  } else if (finished == last_finished && !last) {
    return;  // a line for each finished cell in a log
  }
  if (!tty && last && finished == last_finished) return;
  since_last.Restart();
  last_finished = finished;
  std::ostringstream line;
  line << (tty ? "\r" : "") << "[sweep] " << finished << "/" << p.total << " cells: " << p.done
       << " done, " << p.failed << " failed, " << p.running << " running  " << std::fixed
       << std::setprecision(0) << p.elapsed_s << " s";
  if (finished > 0 && finished < p.total) {
    line << "  ETA " << p.elapsed_s / finished * (p.total - finished) << " s";
  }
  line << (tty ? "   " : "\n");
  std::cerr << line.str() << std::flush;
}

int Sweep(const SweepArguments& args) {
  if (args.cell) {
    RequireFolder(args, "--cell");
    return RunCell(args.target, *args.cell);
  }
  if (args.status) {
    RequireFolder(args, "--status");
    const StoredSweep sweep = LoadSweepFolder(args.target);
    std::vector<std::string> notes;
    const std::vector<CellView> cells = ViewCells(sweep, &notes);
    for (const std::string& note : notes) std::cerr << "attend: note: " << note << "\n";
    std::cout << StatusText(sweep, cells);
    return 0;
  }
  if (args.collect) {
    RequireFolder(args, "--collect");
    const CollectResult result = CollectSweep(LoadSweepFolder(args.target), args.command_line);
    for (const std::string& note : result.notes) std::cerr << "attend: note: " << note << "\n";
    std::cout << result.done << " of " << result.cells << " cells done; scores in " << result.csv
              << ", report in " << result.html << std::endl;
    return 0;
  }

  // The sweep file: given, or the copy in a sweep folder (run again where it stopped).
  SweepPlan plan;
  std::string out = args.out;
  if (IsSweepFolder(args.target)) {
    const StoredSweep stored = LoadSweepFolder(args.target);
    if (!out.empty() && fs::weakly_canonical(out) != fs::weakly_canonical(args.target)) {
      throw ConfigError("--out " + out + ": a sweep folder is run again in place; leave --out out");
    }
    out = args.target;
    const std::string copy = ReadFileText((fs::path(args.target) / "sweep.yaml").string());
    SweepReadOptions options;
    options.text = &copy;
    options.dir = out;
    options.render = !args.dry_run;
    plan = ReadSweepFile(stored.file, options);
  } else {
    std::error_code error;
    if (fs::is_directory(args.target, error)) {
      throw ConfigError(args.target + ": a folder without sweep.json; give a sweep file (YAML) "
                        "or a sweep folder");
    }
    if (out.empty() && !args.dry_run) throw ConfigError("--out is required with a sweep file");
    if (!out.empty() && !args.dry_run && !IsSweepFolder(out) && !IsEmptyOrScenesOnly(out)) {
      throw OutputError(out + ": not empty and not a sweep folder (no sweep.json); give a new "
                        "--out");
    }
    SweepReadOptions options;
    options.dir = out;
    options.render = !args.dry_run;
    plan = ReadSweepFile(args.target, options);
  }
  SlurmSettings slurm = plan.slurm;
  if (args.partition) slurm.partition = *args.partition;
  if (args.time) slurm.time = *args.time;
  if (args.mem) slurm.mem = *args.mem;
  if (args.cpus_per_task) slurm.cpus_per_task = *args.cpus_per_task;
  if (args.throttle) slurm.throttle = *args.throttle;
  const std::string program = SelfExecutable();

  if (args.dry_run) {
    const std::string dir = fs::absolute(out.empty() ? "SWEEP_DIR" : out).lexically_normal();
    std::cout << plan.cells.size() << " cells of attend " << SweepCommandName(plan.command)
              << " (" << plan.inputs.size() << " inputs):\n";
    std::vector<int> indexes;
    StoredSweep sweep;
    sweep.dir = dir;
    for (const SweepCell& cell : plan.cells) {
      std::cout << cell.index << "  " << cell.name << "  " << plan.inputs[cell.input].name
                << "  " << SettingsLine(cell.settings) << "\n";
      indexes.push_back(cell.index);
    }
    if (args.slurm) {
      std::cout << "\nThe batch script:\n"
                << SlurmBatchScript(sweep, indexes, slurm, program, args.command_line);
    } else {
      std::cout << "\nThe commands of each cell:\n";
      for (const SweepCell& cell : plan.cells) {
        const std::string cell_dir = (fs::path(dir) / "cells" / cell.name).string();
        for (std::vector<std::string> command : CellCommands(plan, cell, cell_dir)) {
          command.insert(command.begin(), "attend");
          std::cout << ShellQuote(command) << "\n";
        }
      }
    }
    return 0;
  }

  std::vector<std::string> notes;
  const StoredSweep sweep = PrepareSweepFolder(plan, out, args.extend, &notes);
  const std::vector<CellView> cells = ViewCells(sweep, &notes);
  for (const std::string& note : notes) {
    if (!args.quiet) std::cerr << "attend: note: " << note << "\n";
  }
  const std::vector<int> indexes = CellsToRun(cells, args.retry_failed);
  int done = 0, failed = 0, queued = 0;
  for (const CellView& cell : cells) {
    done += cell.state == CellState::kDone ? 1 : 0;
    failed += cell.state == CellState::kFailed || cell.state == CellState::kKilled ? 1 : 0;
    queued += cell.queued ? 1 : 0;
  }
  if (indexes.empty()) {
    std::cout << sweep.dir << ": nothing to run: " << done << " of " << cells.size()
              << " cells done, " << failed << " failed or killed"
              << (failed > 0 && !args.retry_failed ? " (--retry-failed runs them again)" : "")
              << (queued > 0 ? ", " + std::to_string(queued) + " queued in Slurm" : "")
              << std::endl;
    return 0;
  }
  if (args.slurm) {
    const std::string script =
        SlurmBatchScript(sweep, indexes, slurm, program, args.command_line);
    const SlurmSubmission submission = SubmitSlurmArray(sweep, script);
    std::cout << submission.job_id << std::endl;
    if (!args.quiet) {
      std::cerr << "attend: submitted Slurm job " << submission.job_id << ": " << indexes.size()
                << " cells (" << submission.script_path << "); attend sweep " << sweep.dir
                << " --status\n";
    }
    return 0;
  }

  const int jobs = args.local > 0 ? args.local
                                  : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  std::signal(SIGINT, OnSweepSignal);
  std::signal(SIGTERM, OnSweepSignal);
  const bool tty = isatty(STDERR_FILENO) != 0;
  const LocalSweepResult result = RunSweepLocally(
      sweep, indexes, jobs, &g_sweep_signal, [&](const LocalProgress& progress) {
        if (!args.quiet) PrintProgress(progress, tty);
      });
  if (!args.quiet && tty) std::cerr << "\n";
  const LocalProgress& p = result.progress;
  std::cout << sweep.dir << ": " << p.done << " of " << p.total << " cells done, " << p.failed
            << " failed, in " << Fixed(p.elapsed_s, 1) << " s with " << jobs
            << " at once (the cells took " << Fixed(p.cell_seconds, 1) << " s in all)";
  if (result.stop_signal != 0) {
    std::cout << "; stopped by " << strsignal(result.stop_signal)
              << ": run the same command again to finish";
  }
  std::cout << std::endl;
  if (p.failed > 0 && !args.quiet) {
    std::cerr << "attend: " << p.failed << " cells failed: attend sweep " << sweep.dir
              << " --status says why; --retry-failed runs them again\n";
  }
  if (result.stop_signal != 0) return 128 + result.stop_signal;
  return p.failed > 0 ? static_cast<int>(ExitStatus::kBadInput) : 0;
}

}  // namespace

void AddSweepCommand(CLI::App& app, const std::string& command_line, CommandAction* action) {
  auto args = std::make_shared<SweepArguments>();
  CLI::App* sweep = app.add_subcommand(
      "sweep",
      "A parameter study: a sweep file's grid and zipped lists of configuration keys over its "
      "inputs, each cell (one configuration, one input) run, scored and kept in its own folder "
      "below --out; on this machine (--local N) or as a Slurm job array (--slurm). Running it "
      "again runs only the cells without a result; --status, --collect (sweep.csv and "
      "report.html). docs/SWEEPS.md");
  sweep->add_option("SWEEP", args->target,
                    "The sweep file (YAML), or a sweep folder for --status, --collect, --cell or "
                    "to run it again")
      ->required();
  sweep->add_option("--out", args->out, "The sweep folder (created; a sweep folder of the same "
                                         "sweep is taken up where it stopped)");
  auto* local = sweep->add_option("--local", args->local,
                                  "Run N cells at once on this machine (default: the cores)")
                    ->check(CLI::Range(1, 1024));
  auto* slurm = sweep->add_flag("--slurm", args->slurm,
                                "Submit the cells as a Slurm job array (sbatch) and return");
  local->excludes(slurm);
  sweep->add_option("--partition", args->partition, "Slurm partition (default: the sweep file's)");
  sweep->add_option("--time", args->time, "Slurm time limit of a cell, as sbatch --time");
  sweep->add_option("--mem", args->mem, "Slurm memory of a cell, as sbatch --mem");
  sweep->add_option("--cpus-per-task", args->cpus_per_task, "Slurm CPUs of a cell")
      ->check(CLI::Range(1, 1024));
  sweep->add_option("--throttle", args->throttle,
                    "At most this many Slurm array tasks at once (%M); 0: no limit")
      ->check(CLI::Range(0, 100000));
  auto* status = sweep->add_flag("--status", args->status,
                                 "Say which cells are done, running, failed, killed or waiting");
  auto* collect = sweep->add_flag("--collect", args->collect,
                                  "Gather the scores into DIR/sweep.csv and DIR/report.html");
  sweep->add_flag("--dry-run", args->dry_run,
                  "Print the cells and their commands (with --slurm the batch script); write "
                  "and run nothing");
  sweep->add_flag("--extend", args->extend,
                  "Add the cells a changed sweep file has beyond those of its folder");
  sweep->add_flag("--retry-failed", args->retry_failed,
                  "Run again only the cells that failed or were killed");
  auto* cell = sweep->add_option("--cell", args->cell,
                                 "Compute one cell of a sweep folder by index (what each local "
                                 "process and each Slurm array task runs)");
  sweep->add_flag("--quiet", args->quiet, "No progress line or notes; errors only");
  status->excludes(collect, cell, local, slurm);
  collect->excludes(cell, local, slurm);
  cell->excludes(local, slurm);
  args->command_line = command_line;
  sweep->callback([args, action] { *action = [args] { return Sweep(*args); }; });
}

ATTEND_COMMAND(140, "sweep", AddSweepCommand);

}  // namespace attend
