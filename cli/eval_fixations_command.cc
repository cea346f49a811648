// attend eval-fixations: saliency maps scored against human eye fixations
// (docs/FIXATIONS.md).
#include <iomanip>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "app/evaluate_fixations.h"
#include "cli/cli_options.h"
#include "cli/commands.h"
#include "eval/saliency_baselines.h"
#include "util/error.h"

namespace attend {

namespace {

int EvalFixations(const EvalFixationsRequest& args) {
  FixationEvaluationObserver observer;
  observer.on_unreadable = [](const std::string& error) {
    std::cerr << "attend: error: " << error << "\n";
  };
  if (!args.quiet) {
    observer.on_note = [](const std::string& note) {
      std::cerr << "attend: note: " << note << "\n";
    };
    observer.on_progress = [](int done, int total) {
      std::cerr << "[attend] " << done << "/" << total << " images scored\n";
    };
  }
  const FixationEvaluation result = EvaluateFixations(args, observer);
  std::cout << result.table;
  for (const auto& [name, shares] : result.scanpath_shares) {
    std::cout << name << ": share of fixations in the first k attended regions, k = 1..5:";
    for (const double share : shares) {
      std::cout << " " << std::fixed << std::setprecision(3) << share;
    }
    std::cout << "\n";
  }
  return result.failed.empty() ? 0 : static_cast<int>(ExitStatus::kBadInput);
}

}  // namespace

void AddEvalFixationsCommand(CLI::App& app, const std::string& command_line,
                             CommandAction* action) {
  auto args = std::make_shared<EvalFixationsRequest>();
  CLI::App* cmd = app.add_subcommand(
      "eval-fixations",
      "Score saliency maps (folders of <id>.pfm, as attend saliency writes them) against a "
      "fixation dataset (DIR/stimuli/<id>.*, DIR/fixations/<id>.txt; docs/FIXATIONS.md): NSS, "
      "AUC-Judd, AUC-Borji, shuffled AUC, CC, KL, SIM, information gain over a centre bias; "
      "with scanpath.json in a folder, the share of fixations in its first k regions");
  cmd->add_option("maps", args->maps, "[NAME=]FOLDER of saliency maps (PFM)");
  cmd->add_option("--dataset", args->dataset, "Fixation dataset folder")->required();
  cmd->add_option("--baselines", args->baselines,
                  "Baselines scored in the same run: centre, spectral_residual, fine_grained")
      ->expected(0, 3);
  cmd->add_option("--baseline-blur", args->baseline_blur,
                  "Gaussian blur of the OpenCV baselines, share of the larger side")
      ->check(FiniteRange(0.0, 1.0));
  cmd->add_option("--sigma", args->sigma,
                  "Fixation-density sigma in px at the scored size (one degree of visual angle); "
                  "0: 0.025 x the larger side")
      ->check(FiniteRange(0.0, 1e4));
  cmd->add_option("--max-side", args->max_side,
                  "Score at most this many px on the larger side (maps and fixations scaled); 0: "
                  "the stimulus's size")
      ->check(FiniteRange(0, 100000));
  cmd->add_option("--skip", args->skip,
                  "Leave out the first N images (by id): a held-out split after --first")
      ->check(FiniteRange(0, 1000000));
  cmd->add_option("--first", args->first, "Score only the first N images (by id, after --skip)")
      ->check(FiniteRange(0, 1000000));
  cmd->add_option("--out", args->out, "Write <method>.csv (per image) and fixations.json here");
  cmd->add_flag("--quiet", args->quiet, "No progress or notes");
  args->command_line = command_line;
  cmd->callback([args, action] { *action = [args] { return EvalFixations(*args); }; });
}

ATTEND_COMMAND(120, "eval-fixations", AddEvalFixationsCommand);

}  // namespace attend
