#include "app/scanpath_inputs.h"

#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <system_error>

#include "io/image_file.h"
#include "util/error.h"

namespace attend {

namespace {

namespace fs = std::filesystem;

bool InsideImage(const Fixation& f, cv::Size size) {
  return f.x >= -0.5 && f.y >= -0.5 && f.x < size.width - 0.5 && f.y < size.height - 0.5;
}

// The number at `key` of a region of `file`'s image `id`; InputError when it is not one.
double RegionNumber(const nlohmann::json& region, const char* key, const std::string& file,
                    const std::string& id, size_t index) {
  if (!region.is_object() || !region.contains(key) || !region.at(key).is_number()) {
    throw InputError(file + ": image " + id + ", region " + std::to_string(index + 1) +
                     ": no number \"" + key + "\"");
  }
  return region.at(key).get<double>();
}

}  // namespace

ObservedImage ReadObservedImage(const FixationItem& item, const ObserverReading& reading) {
  ObservedImage image;
  image.id = item.id;
  image.size = ReadImageFile(item.stimulus_path, cv::IMREAD_COLOR, item.stimulus_path).size();
  const std::vector<Fixation> fixations = ReadFixationFile(item.fixations_path, reading.durations);
  for (SubjectFixations& subject : GroupBySubject(fixations)) {
    std::vector<Fixation>& list = subject.fixations;
    if (reading.drop_first && !list.empty()) list.erase(list.begin());
    Scanpath kept;
    for (const Fixation& f : list) {
      if (!InsideImage(f, image.size)) {
        ++image.fixations_outside;
        continue;
      }
      kept.push_back(f);
      if (f.duration_s >= 0.0) image.durations_s.push_back(f.duration_s);
    }
    if (kept.empty()) {
      ++image.observers_left_out;
      continue;
    }
    if (static_cast<int>(kept.size()) > reading.length) kept.resize(reading.length);
    image.observers.push_back(std::move(kept));
  }
  return image;
}

ModelScanpaths ReadModelScanpaths(const std::string& spec) {
  ModelScanpaths model;
  const size_t equals = spec.find('=');
  model.folder = equals == std::string::npos ? spec : spec.substr(equals + 1);
  model.name = equals == std::string::npos ? fs::path(model.folder).filename().string()
                                           : spec.substr(0, equals);
  if (model.name.empty()) model.name = fs::path(model.folder).parent_path().filename().string();
  std::error_code error;
  if (!fs::is_directory(model.folder, error)) {
    throw InputError(model.folder + ": no such folder of saliency maps");
  }
  model.file = (fs::path(model.folder) / "scanpath.json").string();
  if (!fs::is_regular_file(model.file, error)) {
    throw InputError(model.file + ": missing: write it with attend saliency --scanpath K");
  }
  std::ifstream file(model.file);
  try {
    model.paths = nlohmann::json::parse(file);
  } catch (const std::exception& e) {
    throw InputError(model.file + ": not valid JSON: " + e.what());
  }
  if (!model.paths.is_object()) {
    throw InputError(model.file + ": not a JSON object of scanpaths by image");
  }
  return model;
}

Scanpath ModelScanpath(const ModelScanpaths& model, const std::string& id, int length,
                       double duration_s, bool allow_empty) {
  if (!model.paths.contains(id)) {
    throw InputError(model.file + ": no scanpath for image " + id +
                     " (attend saliency --scanpath on the dataset's stimuli writes one per image)");
  }
  const nlohmann::json& regions = model.paths.at(id);
  if (!regions.is_array()) throw InputError(model.file + ": image " + id + ": not a list");
  if (regions.empty() && !allow_empty) {
    throw InputError(model.file + ": image " + id +
                     ": empty scanpath (no region attended; --empty-scanpath zero scores it 0)");
  }
  Scanpath path;
  for (size_t i = 0; i < regions.size() && static_cast<int>(path.size()) < length; ++i) {
    Fixation f;
    f.x = RegionNumber(regions[i], "x", model.file, id, i);
    f.y = RegionNumber(regions[i], "y", model.file, id, i);
    f.duration_s = duration_s;
    if (regions[i].contains("duration_s")) {
      f.duration_s = RegionNumber(regions[i], "duration_s", model.file, id, i);
      if (f.duration_s < 0.0) {
        throw InputError(model.file + ": image " + id + ", region " + std::to_string(i + 1) +
                         ": negative duration_s");
      }
    }
    path.push_back(f);
  }
  return path;
}

}  // namespace attend
