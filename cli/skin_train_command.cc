// attend skin-train: fits the TSL skin colour model (SPEC 2.3, 3.2; docs/SKIN.md) to labelled
// data, chooses its threshold, measures it on a held-out split and writes the model file.
#include <charconv>
#include <cstdint>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "app/train_skin_model.h"
#include "cli/commands.h"
#include "util/error.h"
#include "util/json_text.h"

namespace attend {

namespace {

struct SkinTrainArguments {
  std::vector<std::string> data;
  std::string out;
  std::string rule = "youden";
  double holdout = 0.2;
  uint64_t seed = 1;
  bool overwrite = false;
};

int SkinTrain(const SkinTrainArguments& args, const std::string& command_line) {
  SkinTrainRequest request;
  request.rule = ThresholdRule::Parse(args.rule);
  if (!(args.holdout >= 0.0 && args.holdout < 1.0)) {
    std::ostringstream message;
    message << "--holdout " << args.holdout << ": must be in [0, 1)";
    throw ConfigError(message.str());
  }
  request.data = args.data;
  request.out = args.out;
  request.holdout = args.holdout;
  request.seed = args.seed;
  request.overwrite = args.overwrite;
  request.command_line = command_line;
  std::cout << JsonText(TrainSkinModel(request), 2) << std::endl;
  return 0;
}

}  // namespace

void AddSkinTrainCommand(CLI::App& app, const std::string& command_line, CommandAction* action) {
  auto args = std::make_shared<SkinTrainArguments>();
  CLI::App* command = app.add_subcommand(
      "skin-train",
      "Train the TSL skin colour model (docs/SKIN.md): fit a Gaussian to the (T, S) chrominance "
      "of the skin samples, choose its threshold on the squared Mahalanobis distance by --rule, "
      "measure TPR and FPR on a held-out split and write the model YAML. Prints one JSON object "
      "(samples, mean, covariance, threshold, rule, train and holdout rates).\n"
      "DATA is any mix of:\n"
      "  FILE          text, one 'B G R label' line a sample (0..255 each; label 1 skin, 2 not "
      "skin), as in the UCI Skin Segmentation data set\n"
      "  IMAGE:MASK    an image and its mask, every pixel a sample (mask read as grey, non-zero "
      "= skin; use a lossless format such as PNG)\n"
      "  FOLDER        FOLDER/images/* paired with FOLDER/masks/* of the same stem\n"
      "Samples are numbered in the order given (rows of a file, pixels in raster order, images "
      "by stem); sample n is held out iff a hash of (--seed, n) falls below --holdout, so a "
      "split is reproducible.");
  command->add_option("DATA", args->data, "Labelled data: text file, IMAGE:MASK or folder")
      ->required();
  command->add_option("--out", args->out, "Model file to write (YAML)")->required();
  command
      ->add_option("--rule", args->rule,
                   "Threshold rule: youden (maximise TPR - FPR on the training split) or tpr:X "
                   "(the smallest threshold accepting a share X in (0, 1] of the training skin "
                   "samples)")
      ->capture_default_str();
  command
      ->add_option("--holdout", args->holdout,
                   "Share of the samples held out for evaluation, in [0, 1)")
      ->capture_default_str();
  command->add_option("--seed", args->seed, "Seed of the held-out split, in [0, 2^64)")
      ->check(CLI::Validator(
          [](std::string& text) {
            uint64_t value = 0;
            const auto [end, status] =
                std::from_chars(text.data(), text.data() + text.size(), value);
            return status == std::errc() && end == text.data() + text.size()
                       ? std::string()
                       : "'" + text + "' is not an integer in [0, 2^64)";
          },
          ""))
      ->capture_default_str();
  command->add_flag("--overwrite", args->overwrite, "Replace an existing model file");
  command->callback([args, action, command_line] {
    *action = [args, command_line] { return SkinTrain(*args, command_line); };
  });
}

ATTEND_COMMAND(80, "skin-train", AddSkinTrainCommand);

}  // namespace attend
