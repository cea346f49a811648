// attend eval-scanpaths: the order of attention against human fixation sequences
// (docs/FIXATIONS.md, "Scanpaths").
#include <charconv>
#include <iomanip>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "app/evaluate_scanpaths.h"
#include "cli/cli_options.h"
#include "cli/commands.h"
#include "util/error.h"

namespace attend {

namespace {

struct EvalScanpathsArguments {
  EvalScanpathsRequest request;
  std::string grid = "12x8";
  double bin_ms = 0.0;
  std::string duration_column = "header";
  std::string duration_unit = "ms";
  std::string empty_scanpath = "error";
  bool quiet = false;
};

bool ParseInt(const std::string& text, int* value) {
  const char* end = text.data() + text.size();
  const auto [stop, error] = std::from_chars(text.data(), end, *value);
  return error == std::errc() && stop == end;
}

ScanpathGrid ParseGrid(const std::string& text) {
  const size_t x = text.find('x');
  ScanpathGrid grid;
  if (x == std::string::npos || !ParseInt(text.substr(0, x), &grid.columns) ||
      !ParseInt(text.substr(x + 1), &grid.rows) || grid.columns < 1 || grid.rows < 1) {
    throw ConfigError("--grid " + text + ": expected COLUMNSxROWS, e.g. 12x8");
  }
  return grid;
}

DurationColumn ParseDurationColumn(const std::string& column, const std::string& unit) {
  if (column == "header") return {DurationColumn::Source::kHeader};
  if (column == "none") return {DurationColumn::Source::kNone};
  int number = 0;
  if (!ParseInt(column, &number) || number < 4) {
    throw ConfigError("--duration-column " + column +
                      ": expected header, none or a column number from 4 (1: subject, 2: x, 3: y)");
  }
  if (unit != "ms" && unit != "s") throw ConfigError("--duration-unit " + unit + ": ms or s");
  return {DurationColumn::Source::kColumn, number - 1, unit == "ms" ? 1e-3 : 1.0};
}

int EvalScanpaths(EvalScanpathsArguments args) {
  EvalScanpathsRequest& request = args.request;
  request.scanmatch.grid = ParseGrid(args.grid);
  request.scanmatch.temporal_bin_s = args.bin_ms / 1000.0;
  request.durations = ParseDurationColumn(args.duration_column, args.duration_unit);
  request.empty_scores_zero = args.empty_scanpath == "zero";
  ScanpathEvaluationObserver observer;
  if (!args.quiet) {
    observer.on_note = [](const std::string& note) {
      std::cerr << "attend: note: " << note << "\n";
    };
    observer.on_progress = [](int done, int total) {
      std::cerr << "[attend] " << done << "/" << total << " images scored\n";
    };
  }
  const ScanpathEvaluation result = EvaluateScanpaths(request, observer);
  std::cout << result.table << std::fixed << std::setprecision(3) << result.images
            << " images; ScanMatch threshold " << result.threshold_cells << " cells";
  if (result.model_duration_s >= 0.0) {
    std::cout << "; model fixations last " << result.model_duration_s
              << " s (the observers' median)";
  }
  std::cout << "\n";
  return 0;
}

}  // namespace

void AddEvalScanpathsCommand(CLI::App& app, const std::string& command_line,
                             CommandAction* action) {
  auto args = std::make_shared<EvalScanpathsArguments>();
  EvalScanpathsRequest& r = args->request;
  CLI::App* cmd = app.add_subcommand(
      "eval-scanpaths",
      "Compare the order of attention (MAPS/scanpath.json, attend saliency --scanpath K) with "
      "every observer's fixation sequence of a dataset (docs/FIXATIONS.md, \"Scanpaths\"): "
      "ScanMatch, the sequence score and MultiMatch, beside the human ceiling, centre-bias "
      "scanpaths and each map's peaks");
  cmd->add_option("maps", r.maps, "[NAME=]FOLDER with scanpath.json (and <id>.pfm for peaks)");
  cmd->add_option("--dataset", r.dataset, "Fixation dataset folder")->required();
  cmd->add_option("--baselines", r.baselines,
                  "Scored in the same run: human (each observer against the others), centre, "
                  "peaks")
      ->expected(0, 3);
  cmd->add_option("--out", r.out, "Write <method>.csv (per image) and scanpaths.json here");
  cmd->add_option("--skip", r.skip, "Leave out the first N images (by id)")
      ->check(FiniteRange(0, 1000000));
  cmd->add_option("--first", r.first, "Score only the first N images (by id, after --skip)")
      ->check(FiniteRange(0, 1000000));
  cmd->add_option("--length", r.length, "Compare the first L fixations of every scanpath")
      ->check(FiniteRange(1, 1000));
  cmd->add_flag("--drop-first,!--keep-first", r.drop_first,
                "Leave out each observer's first fixation (the fixation cross's; the default)");
  cmd->add_option("--grid", args->grid, "ScanMatch and sequence-score grid, COLUMNSxROWS");
  cmd->add_option("--scanmatch-threshold", r.scanmatch_threshold,
                  "ScanMatch threshold in cells; 0: 2 sd of the observers' saccade amplitudes")
      ->check(FiniteRange(0.0, 1e6));
  cmd->add_option("--scanmatch-bin-ms", args->bin_ms,
                  "ScanMatch temporal bin in ms (Cristino et al.: 50); 0: off")
      ->check(FiniteRange(0.0, 1e6));
  cmd->add_option("--scanmatch-gap", r.scanmatch.gap, "ScanMatch gap score (<= 0)")
      ->check(FiniteRange(-1e6, 0.0));
  cmd->add_flag("--simplify", r.multimatch.simplify, "MultiMatch: simplify the scanpaths first");
  cmd->add_option("--simplify-amplitude", r.multimatch.amplitude_threshold,
                  "Simplification amplitude threshold, share of the image diagonal")
      ->check(FiniteRange(0.0, 10.0));
  cmd->add_option("--simplify-direction", r.multimatch.direction_threshold_deg,
                  "Simplification direction threshold, degrees")
      ->check(FiniteRange(0.0, 180.0));
  cmd->add_option("--simplify-duration", r.multimatch.duration_threshold_s,
                  "Simplification duration threshold, seconds")
      ->check(FiniteRange(0.0, 1e6));
  cmd->add_option("--centre-draws", r.centre_draws, "Centre-bias scanpaths drawn per image")
      ->check(FiniteRange(1, 100000));
  cmd->add_option("--seed", r.seed, "Seed of the centre-bias draws");
  cmd->add_option("--peak-separation", r.peak_separation,
                  "Peaks: the local-maximum window and least distance between peaks, share of "
                  "the map's larger side")
      ->check(FiniteRange(0.0, 1.0));
  cmd->add_option("--duration-column", args->duration_column,
                  "Fixation durations: header (the column named duration_ms or duration_s), "
                  "none, or a column number (4 = the one after subject x y)");
  cmd->add_option("--duration-unit", args->duration_unit,
                  "Unit of a numbered --duration-column: ms or s");
  cmd->add_option("--empty-scanpath", args->empty_scanpath,
                  "An image whose scanpath.json lists no region: error (exit 3) or zero (it "
                  "scores 0 in every measure)")
      ->check(CLI::IsMember({"error", "zero"}));
  cmd->add_flag("--quiet", args->quiet, "No progress or notes");
  r.command_line = command_line;
  cmd->callback([args, action] { *action = [args] { return EvalScanpaths(*args); }; });
}

ATTEND_COMMAND(125, "eval-scanpaths", AddEvalScanpathsCommand);

}  // namespace attend
