// attend disparity: the dense disparity map of one rectified stereo pair (SPEC 2.3, 3.2;
// docs/DISPARITY.md), with the Middlebury bad-pixel rates of SPEC 4 when ground truth is given.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <system_error>
#include <vector>

#include "app/estimate_disparity.h"
#include "cli/cli_options.h"
#include "cli/commands.h"
#include "config/param_block.h"
#include "features/disparity_feature.h"
#include "util/error.h"
#include "util/json_text.h"
#include "util/strings.h"

namespace attend {

namespace {

namespace fs = std::filesystem;

struct DisparityArguments {
  std::string left;
  std::string right;
  std::string out;
  std::optional<int> max_disparity;
  std::optional<int> window;
  bool subpixel = false;
  bool left_right_check = false;
  std::string gt;
  double gt_scale = 1.0;
  double regions = 0.0;
  std::vector<std::string> sets;
};

// The options: DisparityOptions' defaults, then the `disparity.*` keys of --set, then the
// flags. A key set both ways is a usage error rather than a silent choice of one of them.
DisparityOptions ResolveOptions(const DisparityArguments& args, bool subpixel_given,
                                bool lr_check_given) {
  ParamBlock root = ParamBlock::Parse("", "--set");
  for (const std::string& assignment : args.sets) {
    if (assignment.rfind("disparity.", 0) != 0) {
      throw ConfigError("--set " + assignment +
                        ": attend disparity takes only disparity.KEY=VALUE, KEY one of " +
                        Join(DisparityOptionKeys(), ", "));
    }
    root.Override(assignment);
  }
  const ParamBlock block = root.Child("disparity");
  root.CheckNoUnknownKeys();

  DisparityOptions options = ReadDisparityOptions(block);
  block.CheckNoUnknownKeys();

  const auto only_one = [&block](const std::string& flag, const std::string& key) {
    if (block.Has(key)) {
      throw ConfigError(flag + " and " + block.Where(key) + " both set disparity." + key +
                        "; give one");
    }
  };
  if (args.max_disparity) {
    only_one("--max-disparity", "max_disparity");
    options.max_disparity = *args.max_disparity;
  }
  if (args.window) {
    only_one("--window", "window");
    options.window = *args.window;
  }
  if (subpixel_given) {
    only_one("--subpixel", "subpixel");
    options.subpixel = true;
  }
  if (lr_check_given) {
    only_one("--lr-check/--no-lr-check", "left_right_check");
    options.left_right_check = args.left_right_check;
  }
  // A value out of range is named by where it was given: the flag, or the --set.
  const std::string error = options.Check();
  if (!error.empty()) {
    if (args.max_disparity && error.rfind("max_disparity", 0) == 0) {
      throw ConfigError("--max-disparity " + std::to_string(*args.max_disparity) + ": " + error);
    }
    if (args.window && error.rfind("window", 0) == 0) {
      throw ConfigError("--window " + std::to_string(*args.window) + ": " + error);
    }
    throw ConfigError("disparity options: " + error);
  }
  return options;
}

int Disparity(const DisparityArguments& args, bool subpixel_given, bool lr_check_given) {
  if (Lowercase(fs::path(args.out).extension().string()) != ".pfm") {
    throw ConfigError("--out " + args.out + ": the map is written as PFM; name a .pfm file");
  }
  std::error_code error;
  if (fs::is_directory(args.out, error)) {
    throw OutputError("--out " + args.out + ": is a folder; name a .pfm file");
  }
  DisparityRequest request;
  request.options = ResolveOptions(args, subpixel_given, lr_check_given);
  request.left = args.left;
  request.right = args.right;
  request.out = args.out;
  request.gt = args.gt;
  request.gt_scale = args.gt_scale;
  request.regions = args.regions;
  std::cout << JsonText(EstimateDisparity(request), 2) << std::endl;
  return 0;
}

// The help of the flag that sets the field `key`: its line of the field table and its default.
std::string FlagHelp(std::string_view key) {
  for (const FieldDescription& line : DescribeFields(DisparityOptions::Fields())) {
    if (line.key == key) return line.doc + " (default " + line.fallback + ")";
  }
  return "";
}

}  // namespace

void AddDisparityCommand(CLI::App& app, const std::string&, CommandAction* action) {
  auto args = std::make_shared<DisparityArguments>();
  CLI::App* command = app.add_subcommand(
      "disparity",
      "Dense disparity of a rectified stereo pair by box-filtered ZNCC and semi-global "
      "matching along five paths (the default), or Sun's two-stage dynamic programming of the "
      "thesis (--set disparity.smoothness=hard; docs/DISPARITY.md). LEFT and RIGHT are read as 8-bit images (grey "
      "stays grey, colour is converted to grey by the estimator, 16-bit images are scaled to 8 "
      "bits); a left pixel (x, y) matches the right pixel (x - d, y). Writes the left view's "
      "map to OUT as PFM in pixels and prints one JSON object: the estimator's milliseconds, "
      "the size, the options and, with --gt, the bad-pixel rates bad1 and bad2 (shares of the "
      "known ground-truth pixels off by more than 1 and 2 px). Options not given take "
      "DisparityOptions' defaults; each can be given as a flag or with --set, not both.");
  command->add_option("LEFT", args->left, "Left image")->required();
  command->add_option("RIGHT", args->right, "Right image")->required();
  command
      ->add_option("--out", args->out,
                   "Disparity map to write (.pfm; its folder is created; an existing file is "
                   "replaced only once the new map is complete)")
      ->required();
  command->add_option("--max-disparity", args->max_disparity, FlagHelp("max_disparity"));
  command->add_option("--window", args->window, FlagHelp("window"));
  CLI::Option* subpixel =
      command->add_flag("--subpixel", args->subpixel, "Sub-pixel refinement by a parabola fit");
  CLI::Option* lr_check = command->add_flag(
      "--lr-check,!--no-lr-check", args->left_right_check,
      "Left-right consistency check (default on); inconsistent pixels are filled from their row");
  CLI::Option* gt = command->add_option(
      "--gt", args->gt,
      "Ground truth of the left view: a PFM in pixels, or a one-channel 8- or 16-bit image "
      "(PNG, PGM) holding disparity x --gt-scale; 0 (or infinity in a PFM) is unknown");
  command
      ->add_option("--gt-scale", args->gt_scale,
                   "The ground truth's values are divided by this (default 1; Middlebury: "
                   "tsukuba 16, venus 8, teddy and cones 4)")
      ->check(CLI::Validator(
          [](std::string& text) {
            double value = 0.0;
            try {
              size_t used = 0;
              value = std::stod(text, &used);
              if (used != text.size()) value = 0.0;
            } catch (const std::exception&) {
              value = 0.0;
            }
            return std::isfinite(value) && value > 0.0
                       ? std::string()
                       : "'" + text + "' is not a finite number > 0";
          },
          "POSITIVE"))
      ->needs(gt);
  command
      ->add_option("--regions", args->regions,
                   "With --gt: score the regions of the left image's BIP segmentation larger "
                   "than this share of the image (e.g. 0.01) as targets, each region's disparity "
                   "estimated both ways of the depth section (template, map) against the ground "
                   "truth's median over it (docs/STEREO3D.md)")
      ->check(FiniteRange(0.0, 1.0))
      ->needs(gt);
  AddSetOption(command, &args->sets,
               "Set an option, the value parsed as YAML (repeatable): --set "
               "disparity.KEY=VALUE, with KEY one of\n" +
                   FormatFieldDescriptions(DescribeFields(DisparityOptions::Fields()),
                                           "disparity."));
  command->callback([args, action, subpixel, lr_check] {
    const bool subpixel_given = subpixel->count() > 0;
    const bool lr_check_given = lr_check->count() > 0;
    *action = [args, subpixel_given, lr_check_given] {
      return Disparity(*args, subpixel_given, lr_check_given);
    };
  });
}

ATTEND_COMMAND(40, "disparity", AddDisparityCommand);

}  // namespace attend
