// attend sweep: parameter studies over datasets, on this machine or as a Slurm job array, with
// one report (docs/SWEEPS.md).
#include <unistd.h>

#include <cstring>
#include <iomanip>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>

#include "app/run_sweep.h"
#include "app/sweep_results.h"
#include "cli/cli_options.h"
#include "cli/commands.h"
#include "util/error.h"
#include "util/strings.h"
#include "util/timer.h"

namespace attend {

namespace {

struct SweepArguments {
  SweepRequest request;
  bool status = false;
  bool collect = false;
  std::optional<int> cell;
  bool quiet = false;
};

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

// Prints how a run ended; returns its exit status.
int PrintRun(const SweepRunResult& result, bool retry_failed, bool quiet) {
  if (result.started.empty()) {
    std::cout << result.dir << ": nothing to run: " << result.done << " of " << result.cells
              << " cells done, " << result.failed << " failed or killed"
              << (result.failed > 0 && !retry_failed ? " (--retry-failed runs them again)" : "")
              << (result.queued > 0 ? ", " + std::to_string(result.queued) + " queued in Slurm"
                                    : "")
              << (result.running > 0
                      ? ", " + std::to_string(result.running) + " running in another process"
                      : "")
              << std::endl;
    return 0;
  }
  if (result.submission) {
    std::cout << result.submission->job_id << std::endl;
    if (!quiet) {
      std::cerr << "attend: submitted Slurm job " << result.submission->job_id << ": "
                << result.started.size() << " cells (" << result.submission->script_path
                << "); attend sweep " << result.dir << " --status\n";
    }
    return 0;
  }
  const LocalProgress& p = result.local.progress;
  const int stop_signal = result.local.stop_signal;
  std::cout << result.dir << ": " << p.done << " of " << p.total << " cells done, " << p.failed
            << " failed, in " << Fixed(p.elapsed_s, 1) << " s with " << result.jobs
            << " at once (the cells took " << Fixed(p.cell_seconds, 1) << " s in all)";
  if (stop_signal != 0) {
    std::cout << "; stopped by " << strsignal(stop_signal)
              << ": run the same command again to finish";
  }
  std::cout << std::endl;
  for (const std::string& problem : result.local.problems) {
    std::cerr << "attend: " << problem << "\n";
  }
  if (p.skipped + result.running > 0) {
    std::cout << result.dir << ": " << p.skipped + result.running
              << " cells were left to another process that runs them (attend sweep " << result.dir
              << " --status)" << std::endl;
  }
  if (p.failed > 0 && !quiet) {
    std::cerr << "attend: " << p.failed << " cells failed: attend sweep " << result.dir
              << " --status says why; --retry-failed runs them again\n";
  }
  if (stop_signal != 0) return 128 + stop_signal;
  return p.failed > 0 ? static_cast<int>(ExitStatus::kBadInput) : 0;
}

int Sweep(const SweepArguments& args) {
  const SweepRequest& request = args.request;
  if (args.cell) {
    RequireSweepFolder(request.target, "--cell");
    return RunCell(request.target, *args.cell);
  }
  if (args.status) {
    RequireSweepFolder(request.target, "--status");
    const SweepStatus status = ReadSweepStatus(request.target);
    for (const std::string& note : status.notes) std::cerr << "attend: note: " << note << "\n";
    std::cout << status.text;
    return 0;
  }
  if (args.collect) {
    RequireSweepFolder(request.target, "--collect");
    const CollectResult result =
        CollectSweep(LoadSweepFolder(request.target), request.command_line);
    for (const std::string& note : result.notes) std::cerr << "attend: note: " << note << "\n";
    std::cout << result.done << " of " << result.cells << " cells done; scores in " << result.csv
              << ", report in " << result.html << std::endl;
    return 0;
  }
  const OpenedSweep sweep = OpenSweep(request);
  if (request.dry_run) {
    std::cout << DryRunText(request, sweep);
    return 0;
  }
  const bool tty = isatty(STDERR_FILENO) != 0;
  SweepObserver observer;
  observer.on_note = [&](const std::string& note) {
    if (!args.quiet) std::cerr << "attend: note: " << note << "\n";
  };
  observer.on_progress = [&](const LocalProgress& progress) {
    if (!args.quiet) PrintProgress(progress, tty);
  };
  const SweepRunResult result = RunSweep(request, sweep, observer);
  const bool ran_here = !result.started.empty() && !result.submission;
  if (ran_here && !args.quiet && tty) std::cerr << "\n";
  return PrintRun(result, request.retry_failed, args.quiet);
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
  sweep->add_option("SWEEP", args->request.target,
                    "The sweep file (YAML), or a sweep folder for --status, --collect, --cell or "
                    "to run it again")
      ->required();
  sweep->add_option("--out", args->request.out, "The sweep folder (created; a sweep folder of the same "
                                         "sweep is taken up where it stopped)");
  auto* local = sweep->add_option("--local", args->request.local,
                                  "Run N cells at once on this machine (default: the cores)")
                    ->check(FiniteRange(1, 1024));
  auto* slurm = sweep->add_flag("--slurm", args->request.slurm,
                                "Submit the cells as a Slurm job array (sbatch) and return");
  local->excludes(slurm);
  sweep->add_option("--partition", args->request.slurm_overrides.partition, "Slurm partition (default: the sweep file's)");
  sweep->add_option("--time", args->request.slurm_overrides.time, "Slurm time limit of a cell, as sbatch --time");
  sweep->add_option("--mem", args->request.slurm_overrides.mem, "Slurm memory of a cell, as sbatch --mem");
  sweep->add_option("--cpus-per-task", args->request.slurm_overrides.cpus_per_task, "Slurm CPUs of a cell")
      ->check(FiniteRange(1, 1024));
  sweep->add_option("--throttle", args->request.slurm_overrides.throttle,
                    "At most this many Slurm array tasks at once (%M); 0: no limit")
      ->check(FiniteRange(0, 100000));
  auto* status = sweep->add_flag("--status", args->status,
                                 "Say which cells are done, running, failed, killed or waiting");
  auto* collect = sweep->add_flag("--collect", args->collect,
                                  "Gather the scores into DIR/sweep.csv and DIR/report.html");
  sweep->add_flag("--dry-run", args->request.dry_run,
                  "Print the cells and their commands (with --slurm the batch script); write "
                  "and run nothing");
  sweep->add_flag("--extend", args->request.extend,
                  "Add the cells a changed sweep file has beyond those of its folder");
  sweep->add_flag("--retry-failed", args->request.retry_failed,
                  "Run again only the cells that failed or were killed");
  auto* cell = sweep->add_option("--cell", args->cell,
                                 "Compute one cell of a sweep folder by index (what each local "
                                 "process and each Slurm array task runs)");
  sweep->add_flag("--quiet", args->quiet, "No progress line or notes; errors only");
  status->excludes(collect, cell, local, slurm);
  collect->excludes(cell, local, slurm);
  cell->excludes(local, slurm);
  args->request.command_line = command_line;
  sweep->callback([args, action] { *action = [args] { return Sweep(*args); }; });
}

ATTEND_COMMAND(140, "sweep", AddSweepCommand);

}  // namespace attend
