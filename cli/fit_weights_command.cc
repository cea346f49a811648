// attend fit-weights: feature weights fitted to eye fixations on a training split (issue 14,
// docs/FIXATIONS.md).
#include <algorithm>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <memory>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "cli/cli_options.h"
#include "cli/commands.h"
#include "cli/home.h"
#include "eval/fixation_data.h"
#include "eval/weight_fit.h"
#include "io/image_file.h"
#include "pipeline/options_io.h"
#include "pipeline/still_saliency.h"
#include "util/error.h"

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
  const std::string config_path = args.config.empty() ? DefaultConfigPath() : args.config;
  AttendOptions options = LoadOptions(config_path, args.sets);
  const FixationDataset dataset = OpenFixationDataset(args.dataset);
  std::vector<FixationItem> items = dataset.items;
  if (static_cast<int>(items.size()) > args.train) items.resize(args.train);
  const StillSaliency still(options, AttendHome());

  std::vector<FitSample> samples;
  std::vector<std::string> names;
  for (const FixationItem& item : items) {
    const cv::Mat bgr = ReadImageFile(item.stimulus_path, cv::IMREAD_COLOR, item.stimulus_path);
    const StillMaps maps = still.Compute(bgr, true, 0);
    names = maps.feature_names;
    const int side = std::max(bgr.cols, bgr.rows);
    const double scale = side > args.max_side ? static_cast<double>(args.max_side) / side : 1.0;
    const cv::Size size(std::max(1, static_cast<int>(std::lround(bgr.cols * scale))),
                        std::max(1, static_cast<int>(std::lround(bgr.rows * scale))));
    FitSample sample;
    for (const cv::Mat& feature : maps.features) {
      cv::Mat small;
      cv::resize(feature, small, size, 0, 0, cv::INTER_AREA);
      sample.features.push_back(small);
    }
    for (Fixation f : ReadFixationFile(item.fixations_path)) {
      f.x *= scale;
      f.y *= scale;
      if (f.x > -0.5 && f.y > -0.5 && f.x < size.width - 0.5 && f.y < size.height - 0.5) {
        sample.fixations.push_back(f);
      }
    }
    samples.push_back(std::move(sample));
  }
  if (names.empty()) throw ConfigError(config_path + ": no enabled feature to weigh");
  if (names.size() > 8) throw ConfigError(config_path + ": fit-weights weighs at most 8 features");

  WeightFitOptions fit_options;
  fit_options.saliency = options.saliency;
  fit_options.step = args.step;
  const WeightFit fit = FitWeights(samples, fit_options);
  for (FeatureSpec& spec : options.features) {
    const auto at = std::find(names.begin(), names.end(), spec.name);
    if (spec.enabled && at != names.end()) spec.weight = fit.weights[at - names.begin()];
  }
  {
    std::ofstream file(args.out);
    file << "# attend fit-weights --dataset " << args.dataset << " --config " << config_path
         << " --train " << args.train << " --step " << args.step << " --max-side "
         << args.max_side << "\n# images 1.." << items.size()
         << " by id were used for fitting: score on the others (--skip " << items.size()
         << ")\n"
         << OptionsToYaml(options) << "\n";
    if (!file) throw InputError(args.out + ": cannot be written");
  }
  if (!args.quiet) {
    std::cout << std::fixed << std::setprecision(2) << "weights (" << fit.candidates
              << " tried, training mean NSS " << std::setprecision(3) << fit.nss << " on "
              << samples.size() << " images):";
    for (size_t i = 0; i < names.size(); ++i) {
      std::cout << " " << names[i] << " " << std::setprecision(2) << fit.weights[i];
    }
    std::cout << "\nwritten to " << args.out << "; score the held-out images with "
              << "attend eval-fixations ... --skip " << items.size() << std::endl;
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
      ->check(CLI::Range(1, 1000000));
  cmd->add_option("--step", args->step, "Grid step of the weights")->check(CLI::Range(0.01, 1.0));
  cmd->add_option("--max-side", args->max_side,
                  "Fit on maps of at most this many px on the larger side")
      ->check(CLI::Range(16, 4096));
  cmd->add_option("--out", args->out, "The fitted configuration (YAML)")->required();
  cmd->add_flag("--quiet", args->quiet, "No report");
  cmd->callback([args, action] { *action = [args] { return FitWeightsCommand(*args); }; });
}

}  // namespace attend
