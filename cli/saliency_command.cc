// attend saliency: the pre-attentive stage on still images (docs/FIXATIONS.md).
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <system_error>
#include <vector>

#include "app/saliency_maps.h"
#include "cli/cli_options.h"
#include "cli/commands.h"
#include "app/home.h"
#include "io/sequence.h"
#include "pipeline/options_io.h"
#include "util/error.h"

namespace attend {

namespace {

namespace fs = std::filesystem;

struct SaliencyArguments {
  std::vector<std::string> inputs;
  std::string out;
  std::string config;
  std::vector<std::string> sets;
  bool features = false;
  int scanpath = 0;
  std::string scanpath_point = "centre";
  bool quiet = false;
  std::string command_line;
};

// The images named, a folder standing for the image files in it (ListFrameFiles).
std::vector<std::string> ListImages(const std::vector<std::string>& inputs) {
  std::vector<std::string> images;
  for (const std::string& input : inputs) {
    std::error_code error;
    if (fs::is_directory(input, error)) {
      const std::vector<std::string> listed = ListFrameFiles(input, "saliency");
      images.insert(images.end(), listed.begin(), listed.end());
    } else if (fs::exists(input, error)) {
      images.push_back(input);
    } else {
      throw InputError(input + ": no such image or folder");
    }
  }
  if (images.empty()) throw InputError("saliency: no image files in the given folders");
  OutputStems(images, "maps STEM.pfm");
  return images;
}

int Saliency(const SaliencyArguments& args) {
  SaliencyMapsRequest request;
  request.config_path = args.config.empty() ? DefaultConfigPath() : args.config;
  request.options = LoadOptions(request.config_path, args.sets);
  request.images = ListImages(args.inputs);
  request.out = args.out;
  request.home = AttendHome();
  request.features = args.features;
  request.scanpath = args.scanpath;
  request.scanpath_point =
      args.scanpath_point == "peak" ? ScanpathPoint::kPeak : ScanpathPoint::kCentre;
  request.command_line = args.command_line;
  SaliencyMapsObserver observer;
  observer.on_left_out = [&args](const std::string& name) {
    if (!args.quiet) {
      std::cerr << "attend: note: feature '" << name
                << "' needs stereo and is left out for still images\n";
    }
  };
  // Named, and the other images are still processed; the exit status says it at the end.
  observer.on_unreadable = [](const InputError& e) {
    std::cerr << "attend: error: " << e.what() << "\n";
  };
  const SaliencyMapsResult result = WriteSaliencyMaps(request, observer);
  if (!args.quiet) {
    std::cout << result.written << " saliency maps in " << fs::path(args.out).string();
    if (!result.failed.empty()) {
      std::cout << "; " << result.failed.size() << " images could not be read";
    }
    std::cout << std::endl;
  }
  return result.failed.empty() ? 0 : static_cast<int>(ExitStatus::kBadInput);
}

}  // namespace

void AddSaliencyCommand(CLI::App& app, const std::string& command_line, CommandAction* action) {
  auto args = std::make_shared<SaliencyArguments>();
  CLI::App* cmd = app.add_subcommand(
      "saliency",
      "The pre-attentive stage on still images, each on its own: OUT/<stem>.pfm and "
      "OUT/<stem>.png (at the image's size), OUT/saliency.json; with --features "
      "OUT/features/<name>/<stem>.pfm|png; with --scanpath K OUT/scanpath.json (the first K "
      "targets attention selects). OUT may hold other files: only these are written. "
      "Features that need stereo are left out (docs/FIXATIONS.md)");
  cmd->add_option("inputs", args->inputs, "Images, or folders of images")->required();
  cmd->add_option("--out", args->out, "Output folder")->required();
  cmd->add_option("--config", args->config,
                  "Configuration YAML (default: configs/default.yaml of the attend home)");
  AddSetOption(cmd, &args->sets, "Override a configuration key, the value parsed as YAML");
  cmd->add_flag("--features", args->features, "Also write every feature's normalised map");
  cmd->add_option("--scanpath", args->scanpath,
                  "Also write the first K attended regions of each image (scanpath.json)")
      ->check(FiniteRange(0, 100));
  cmd->add_option("--scanpath-point", args->scanpath_point,
                  "Where a step lands in its target: centre (of its box) or peak (the most "
                  "salient pixel in its box)")
      ->check(CLI::IsMember({"centre", "peak"}));
  cmd->add_flag("--quiet", args->quiet, "No report; errors only");
  args->command_line = command_line;
  cmd->callback([args, action] { *action = [args] { return Saliency(*args); }; });
}

ATTEND_COMMAND(110, "saliency", AddSaliencyCommand);

}  // namespace attend
