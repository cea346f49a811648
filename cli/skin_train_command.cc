// attend skin-train: fits the TSL skin colour model (SPEC 2.3, 3.2; docs/SKIN.md) to labelled
// data, chooses its threshold, measures it on a held-out split and writes the model file.
#include <algorithm>
#include <charconv>
#include <cstdint>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <system_error>
#include <vector>

#include "cli/commands.h"
#include "features/skin_training.h"
#include "util/error.h"
#include "util/strings.h"
#include "util/timer.h"
#include "util/json_text.h"

namespace attend {

namespace {

namespace fs = std::filesystem;

struct SkinTrainArguments {
  std::vector<std::string> data;
  std::string out;
  std::string rule = "youden";
  double holdout = 0.2;
  uint64_t seed = 1;
  bool overwrite = false;
};

// The regular, non-hidden files of a folder by stem. Two files with one stem are ambiguous.
std::map<std::string, fs::path> FilesByStem(const fs::path& folder, const std::string& item) {
  std::map<std::string, fs::path> files;
  std::error_code error;
  for (const fs::directory_entry& entry : fs::directory_iterator(folder, error)) {
    const std::string name = entry.path().filename().string();
    if (name.empty() || name[0] == '.' || !entry.is_regular_file(error)) continue;
    const std::string stem = entry.path().stem().string();
    const auto [it, inserted] = files.emplace(stem, entry.path());
    if (!inserted) {
      throw InputError(item + ": " + it->second.string() + " and " + entry.path().string() +
                       " have the same stem '" + stem + "'; cannot tell which one to pair");
    }
  }
  if (error)
    throw InputError(folder.string() + ": cannot list the folder (" + error.message() + ")");
  return files;
}

// A folder with images/ and masks/: every image with the mask of the same stem, in order of
// the stems.
void ReadFolder(const std::string& item, const SkinSampleSink& sink) {
  const fs::path images_folder = fs::path(item) / "images";
  const fs::path masks_folder = fs::path(item) / "masks";
  std::error_code error;
  if (!fs::is_directory(images_folder, error) || !fs::is_directory(masks_folder, error)) {
    throw InputError(item + ": a data folder needs the subfolders images/ and masks/");
  }
  const std::map<std::string, fs::path> images = FilesByStem(images_folder, item);
  const std::map<std::string, fs::path> masks = FilesByStem(masks_folder, item);
  if (images.empty()) throw InputError(images_folder.string() + ": holds no images");
  for (const auto& [stem, image] : images) {
    if (masks.count(stem) == 0) {
      throw InputError(image.string() + ": no mask with the stem '" + stem + "' in " +
                       masks_folder.string());
    }
  }
  for (const auto& [stem, mask] : masks) {
    if (images.count(stem) == 0) {
      throw InputError(mask.string() + ": no image with the stem '" + stem + "' in " +
                       images_folder.string());
    }
  }
  for (const auto& [stem, image] : images) {
    ReadSkinImagePair(image.string(), masks.at(stem).string(), sink);
  }
}

// One DATA item: a folder, a `B G R label` text file, or IMAGE:MASK.
void ReadDataItem(const std::string& item, const SkinSampleSink& sink) {
  std::error_code error;
  if (fs::is_directory(item, error)) return ReadFolder(item, sink);
  if (fs::exists(item, error)) return ReadSkinText(item, sink);
  const size_t first_colon = item.find(':');
  if (first_colon == std::string::npos) throw InputError(item + ": no such file or folder");
  // Paths may hold colons themselves: split at the first colon that leaves an existing image.
  size_t colon = first_colon;
  for (size_t at = first_colon; at != std::string::npos; at = item.find(':', at + 1)) {
    if (fs::exists(item.substr(0, at), error)) {
      colon = at;
      break;
    }
  }
  ReadSkinImagePair(item.substr(0, colon), item.substr(colon + 1), sink);
}

nlohmann::json Rate(double rate) { return rate >= 0.0 ? nlohmann::json(rate) : nlohmann::json(); }

nlohmann::json Rates(const SkinRates& rates) {
  return {{"tpr", Rate(rates.tpr)},
          {"fpr", Rate(rates.fpr)},
          {"skin", rates.skin},
          {"nonskin", rates.nonskin}};
}

int SkinTrain(const SkinTrainArguments& args, const std::string& command_line) {
  const Stopwatch watch;
  const ThresholdRule rule = ThresholdRule::Parse(args.rule);
  if (!(args.holdout >= 0.0 && args.holdout < 1.0)) {
    std::ostringstream message;
    message << "--holdout " << args.holdout << ": must be in [0, 1)";
    throw ConfigError(message.str());
  }
  std::error_code error;
  if (fs::is_directory(args.out, error)) {
    throw OutputError(args.out + ": is a folder; --out names the model file to write");
  }
  if (fs::exists(args.out, error) && !args.overwrite) {
    throw OutputError(args.out + ": already exists (pass --overwrite to replace it)");
  }

  SkinSplit split;
  split.seed = args.seed;
  split.holdout_fraction = args.holdout;
  const SkinSampleSink sink = split.Sink();
  for (const std::string& item : args.data) ReadDataItem(item, sink);
  const double read_ms = watch.ElapsedMs();
  const size_t skin = split.training.skin.size() + split.held_out.skin.size();
  if (skin == 0) {
    throw InputError(Join(args.data, " ") +
                     ": the data holds no skin samples (label 1, or non-zero mask pixels)");
  }

  SkinModel model = FitSkinModel(split.training, rule);
  const SkinRates training = EvaluateSkinModel(model, split.training);
  const SkinRates held_out = EvaluateSkinModel(model, split.held_out);
  SkinModel::Provenance& provenance = model.provenance;
  provenance.command = command_line;
  provenance.data = Join(args.data, " ");
  provenance.holdout_fraction = args.holdout;
  provenance.seed = args.seed;
  provenance.holdout_tpr = held_out.tpr;
  provenance.holdout_fpr = held_out.fpr;
  // The folder is made only now, so that bad data leaves nothing behind.
  const fs::path parent = fs::path(args.out).parent_path();
  if (!parent.empty()) {
    fs::create_directories(parent, error);
    if (error) {
      throw OutputError(parent.string() + ": cannot create the folder (" + error.message() + ")");
    }
  }
  SaveSkinModel(model, args.out);

  const Eigen::Matrix2d& c = model.covariance;
  const nlohmann::json report = {
      {"model", args.out},
      {"samples",
       {{"skin", skin},
        {"nonskin", split.training.nonskin.size() + split.held_out.nonskin.size()}}},
      {"mean", {model.mean[0], model.mean[1]}},
      {"covariance", {c(0, 0), c(0, 1), c(1, 0), c(1, 1)}},
      {"threshold", model.threshold},
      {"rule", provenance.rule},
      {"holdout_fraction", args.holdout},
      {"seed", args.seed},
      {"train", Rates(training)},
      {"holdout", Rates(held_out)},
      {"milliseconds", {{"read", read_ms}, {"total", watch.ElapsedMs()}}}};
  std::cout << JsonText(report, 2) << std::endl;
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

}  // namespace attend
