#include "app/saliency_maps.h"

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <system_error>

#include "io/image_file.h"
#include "io/pfm.h"
#include "pipeline/still_saliency.h"
#include "util/json_text.h"

namespace attend {

namespace {

namespace fs = std::filesystem;

void WritePreview(const std::string& path, const cv::Mat& map) {
  cv::Mat preview;
  map.convertTo(preview, CV_8U, 255.0);
  if (!WriteImage(path, preview)) throw InputError(path + ": cannot be written");
}

void WriteMaps(const fs::path& folder, const std::string& stem, const cv::Mat& map) {
  std::error_code error;
  fs::create_directories(folder, error);
  if (error) throw InputError(folder.string() + ": cannot create the folder: " + error.message());
  WritePfm((folder / (stem + ".pfm")).string(), map);
  WritePreview((folder / (stem + ".png")).string(), map);
}

}  // namespace

SaliencyMapsResult WriteSaliencyMaps(const SaliencyMapsRequest& request,
                                     const SaliencyMapsObserver& observer) {
  std::vector<std::string> dropped;
  const StillSaliency still(request.options, request.home, &dropped);
  for (const std::string& name : dropped) {
    if (observer.on_left_out) observer.on_left_out(name);
  }
  const fs::path out(request.out);
  nlohmann::json entries = nlohmann::json::array();
  nlohmann::json scanpaths = nlohmann::json::object();
  SaliencyMapsResult result;
  for (const std::string& path : request.images) {
    const std::string stem = fs::path(path).stem().string();
    cv::Mat bgr;
    try {
      bgr = ReadImageFile(path, cv::IMREAD_COLOR, path);
    } catch (const InputError& e) {
      // Named, and the other images are still processed.
      if (observer.on_unreadable) observer.on_unreadable(e);
      result.failed.push_back(path);
      continue;
    }
    const StillMaps maps = still.Compute(bgr, request.features, request.scanpath,
                                         request.scanpath_point);
    WriteMaps(out, stem, maps.saliency);
    for (size_t i = 0; i < maps.features.size(); ++i) {
      WriteMaps(out / "features" / maps.feature_names[i], stem, maps.features[i]);
    }
    if (request.scanpath > 0) {
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
  result.written = static_cast<int>(entries.size());
  const nlohmann::json summary = {{"images", entries},
                                  {"failed", result.failed},
                                  {"features_left_out", dropped},
                                  {"config", request.config_path},
                                  {"command", request.command_line}};
  std::error_code error;
  fs::create_directories(out, error);
  auto write_json = [&](const std::string& name, const nlohmann::json& value) {
    const fs::path file_path = out / name;
    std::ofstream file(file_path);
    file << JsonText(value, 2) << "\n";
    if (!file) throw InputError(file_path.string() + ": cannot be written");
  };
  write_json("saliency.json", summary);
  if (request.scanpath > 0) write_json("scanpath.json", scanpaths);
  return result;
}

}  // namespace attend
