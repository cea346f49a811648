// attend saliency: the pre-attentive stage on still images (issue 14, docs/FIXATIONS.md).
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <system_error>
#include <vector>

#include "cli/cli_options.h"
#include "cli/commands.h"
#include "cli/home.h"
#include "io/image_file.h"
#include "io/pfm.h"
#include "io/sequence.h"
#include "pipeline/options_io.h"
#include "pipeline/still_saliency.h"
#include "util/error.h"
#include "util/json_text.h"

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

void WritePreview(const std::string& path, const cv::Mat& map) {
  cv::Mat preview;
  map.convertTo(preview, CV_8U, 255.0);
  if (!cv::imwrite(path, preview)) throw InputError(path + ": cannot be written");
}

void WriteMaps(const fs::path& folder, const std::string& stem, const cv::Mat& map) {
  std::error_code error;
  fs::create_directories(folder, error);
  if (error) throw InputError(folder.string() + ": cannot create the folder: " + error.message());
  WritePfm((folder / (stem + ".pfm")).string(), map);
  WritePreview((folder / (stem + ".png")).string(), map);
}

int Saliency(const SaliencyArguments& args) {
  const std::string config_path = args.config.empty() ? DefaultConfigPath() : args.config;
  const AttendOptions options = LoadOptions(config_path, args.sets);
  const std::vector<std::string> images = ListImages(args.inputs);
  std::vector<std::string> dropped;
  const StillSaliency still(options, AttendHome(), &dropped);
  for (const std::string& name : dropped) {
    if (!args.quiet) {
      std::cerr << "attend: note: feature '" << name
                << "' needs stereo and is left out for still images\n";
    }
  }
  const fs::path out(args.out);
  nlohmann::json entries = nlohmann::json::array();
  nlohmann::json scanpaths = nlohmann::json::object();
  std::vector<std::string> failed;
  for (const std::string& path : images) {
    const std::string stem = fs::path(path).stem().string();
    cv::Mat bgr;
    try {
      bgr = ReadImageFile(path, cv::IMREAD_COLOR, path);
    } catch (const InputError& e) {
      // Named, and the other images are still processed; the exit status says it at the end.
      std::cerr << "attend: error: " << e.what() << "\n";
      failed.push_back(path);
      continue;
    }
    const StillMaps maps = still.Compute(bgr, args.features, args.scanpath);
    WriteMaps(out, stem, maps.saliency);
    for (size_t i = 0; i < maps.features.size(); ++i) {
      WriteMaps(out / "features" / maps.feature_names[i], stem, maps.features[i]);
    }
    if (args.scanpath > 0) {
      nlohmann::json path_json = nlohmann::json::array();
      for (size_t i = 0; i < maps.scanpath.size(); ++i) {
        const cv::Rect& box = maps.scanpath_boxes[i];
        path_json.push_back({{"x", maps.scanpath[i].x},
                             {"y", maps.scanpath[i].y},
                             {"bbox", {box.x, box.y, box.width, box.height}}});
      }
      scanpaths[stem] = path_json;
    }
    entries.push_back({{"image", path},
                       {"stem", stem},
                       {"size", {maps.image_size.width, maps.image_size.height}},
                       {"working_size", {maps.working_size.width, maps.working_size.height}}});
  }
  const nlohmann::json summary = {{"images", entries},
                                  {"failed", failed},
                                  {"features_left_out", dropped},
                                  {"config", config_path},
                                  {"command", args.command_line}};
  std::error_code error;
  fs::create_directories(out, error);
  auto write_json = [&](const std::string& name, const nlohmann::json& value) {
    const fs::path file_path = out / name;
    std::ofstream file(file_path);
    file << JsonText(value, 2) << "\n";
    if (!file) throw InputError(file_path.string() + ": cannot be written");
  };
  write_json("saliency.json", summary);
  if (args.scanpath > 0) write_json("scanpath.json", scanpaths);
  if (!args.quiet) {
    std::cout << entries.size() << " saliency maps in " << out.string();
    if (!failed.empty()) std::cout << "; " << failed.size() << " images could not be read";
    std::cout << std::endl;
  }
  return failed.empty() ? 0 : static_cast<int>(ExitStatus::kBadInput);
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
      ->check(CLI::Range(0, 100));
  cmd->add_flag("--quiet", args->quiet, "No report; errors only");
  args->command_line = command_line;
  cmd->callback([args, action] { *action = [args] { return Saliency(*args); }; });
}

}  // namespace attend
