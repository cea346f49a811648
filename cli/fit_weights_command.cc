// attend fit-weights: feature weights fitted to eye fixations on a training split
// (docs/FIXATIONS.md).
#include <iomanip>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "app/fit_feature_weights.h"
#include "cli/cli_options.h"
#include "cli/commands.h"
#include "app/home.h"
#include "pipeline/options_io.h"

namespace attend {

namespace {

struct FitWeightsArguments {
  std::string dataset;
  std::string config;
  std::vector<std::string> sets;
  int train = 100;
  double step = 0.1;
  int max_side = 128;
  std::string out;
  bool quiet = false;
};

int FitWeightsCommand(const FitWeightsArguments& args) {
  FitWeightsRequest request;
  request.config_path = args.config.empty() ? DefaultConfigPath() : args.config;
  request.options = LoadOptions(request.config_path, args.sets);
  request.dataset = args.dataset;
  request.home = AttendHome();
  request.train = args.train;
  request.step = args.step;
  request.max_side = args.max_side;
  request.out = args.out;
  const FitWeightsResult result = FitFeatureWeights(request);
  if (!args.quiet) {
    std::cout << std::fixed << std::setprecision(2) << "weights (" << result.fit.candidates
              << " tried, training mean NSS " << std::setprecision(3) << result.fit.nss << " on "
              << result.images << " images):";
    for (size_t i = 0; i < result.features.size(); ++i) {
      std::cout << " " << result.features[i] << " " << std::setprecision(2) << result.fit.weights[i];
    }
    std::cout << "\nwritten to " << args.out << "; score the held-out images with "
              << "attend eval-fixations ... --skip " << result.images << std::endl;
  }
  return 0;
}

}  // namespace

void AddFitWeightsCommand(CLI::App& app, const std::string& command_line, CommandAction* action) {
  (void)command_line;
  auto args = std::make_shared<FitWeightsArguments>();
  CLI::App* cmd = app.add_subcommand(
      "fit-weights",
      "Fit the feature weights of a configuration to a fixation dataset: the weights on a grid "
      "over the simplex with the highest mean NSS on the first --train images (by id); writes "
      "the configuration with those weights (docs/FIXATIONS.md)");
  cmd->add_option("--dataset", args->dataset, "Fixation dataset folder")->required();
  cmd->add_option("--config", args->config, "Configuration whose feature weights are fitted");
  AddSetOption(cmd, &args->sets, "Override a configuration key, the value parsed as YAML");
  cmd->add_option("--train", args->train, "Images used for fitting: the first N by id")
      ->check(FiniteRange(1, 1000000));
  cmd->add_option("--step", args->step, "Grid step of the weights")->check(FiniteRange(0.01, 1.0));
  cmd->add_option("--max-side", args->max_side,
                  "Fit on maps of at most this many px on the larger side")
      ->check(FiniteRange(16, 4096));
  cmd->add_option("--out", args->out, "The fitted configuration (YAML)")->required();
  cmd->add_flag("--quiet", args->quiet, "No report");
  cmd->callback([args, action] { *action = [args] { return FitWeightsCommand(*args); }; });
}

ATTEND_COMMAND(130, "fit-weights", AddFitWeightsCommand);

}  // namespace attend
