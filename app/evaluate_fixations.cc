#include "app/evaluate_fixations.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>
#include <system_error>

#include "eval/fixation_data.h"
#include "eval/fixation_metrics.h"
#include "eval/saliency_baselines.h"
#include "io/image_file.h"
#include "io/pfm.h"
#include "util/error.h"
#include "util/json_text.h"
#include "util/opencv_extra.h"

namespace attend {

namespace {

namespace fs = std::filesystem;

struct Method {
  std::string name;
  std::string folder;                                // empty for a baseline
  std::vector<std::vector<double>> values;           // per metric, per image
  nlohmann::json scanpaths;                          // the folder's scanpath.json, or null
  std::vector<std::vector<double>> scanpath_shares;  // per k, per image
  std::vector<std::string> ids;
};

// The scale that brings `size` to at most `max_side` on its larger side (1 when it is smaller).
double ScoringScale(cv::Size size, int max_side) {
  const int side = std::max(size.width, size.height);
  return max_side > 0 && side > max_side ? static_cast<double>(max_side) / side : 1.0;
}

cv::Mat ToSize(const cv::Mat& map, cv::Size size) {
  if (map.size() == size) return map;
  // A constant map stays constant: OpenCV's area interpolation of floats leaves rounding
  // differences in the last bits, which the AUCs and CC would read as structure.
  double low = 0.0, high = 0.0;
  cv::minMaxLoc(map, &low, &high);
  if (low == high) return cv::Mat(size, map.type(), cv::Scalar(low));
  cv::Mat out;
  cv::resize(map, out, size, 0, 0, map.cols > size.width ? cv::INTER_AREA : cv::INTER_LINEAR);
  return out;
}

// The share of `fixations` inside the union of the first k boxes, k = 1..kScanpathDepth (a box
// of fewer regions repeats the last share).
std::vector<double> ScanpathShares(const nlohmann::json& path, double scale,
                                   const std::vector<Fixation>& fixations) {
  std::vector<cv::Rect2d> boxes;
  for (const nlohmann::json& step : path) {
    const nlohmann::json& b = step.at("bbox");
    boxes.emplace_back(b.at(0).get<double>() * scale, b.at(1).get<double>() * scale,
                       b.at(2).get<double>() * scale, b.at(3).get<double>() * scale);
  }
  std::vector<double> shares(kScanpathDepth, 0.0);
  if (fixations.empty()) return shares;
  for (int k = 1; k <= kScanpathDepth; ++k) {
    int inside = 0;
    for (const Fixation& f : fixations) {
      for (int i = 0; i < std::min<int>(k, boxes.size()); ++i) {
        if (boxes[i].contains({f.x, f.y})) {
          ++inside;
          break;
        }
      }
    }
    shares[k - 1] = static_cast<double>(inside) / fixations.size();
  }
  return shares;
}

std::string Table(const std::vector<Method>& methods) {
  std::ostringstream out;
  out << std::fixed << std::setprecision(3);
  out << "| method | images |";
  for (const std::string& metric : FixationMetricNames()) out << " " << metric << " |";
  out << "\n|---|---:|";
  for (size_t i = 0; i < FixationMetricNames().size(); ++i) out << "---:|";
  out << "\n";
  for (const Method& method : methods) {
    out << "| " << method.name << " | " << method.ids.size() << " |";
    for (const std::vector<double>& values : method.values) {
      const MeanInterval m = MeanWithInterval(values);
      out << " " << m.mean << " +- " << (m.high - m.mean) << " |";
    }
    out << "\n";
  }
  return out.str();
}

// The methods to score: the map folders (NAME=FOLDER or FOLDER, with their scanpaths when
// there are) and the baselines, each with its empty score lists.
std::vector<Method> MethodsOf(const EvalFixationsRequest& request) {
  std::vector<Method> methods;
  for (const std::string& spec : request.maps) {
    Method method;
    const size_t equals = spec.find('=');
    method.folder = equals == std::string::npos ? spec : spec.substr(equals + 1);
    method.name = equals == std::string::npos ? fs::path(method.folder).filename().string()
                                              : spec.substr(0, equals);
    if (method.name.empty())
      method.name = fs::path(method.folder).parent_path().filename().string();
    std::error_code error;
    if (!fs::is_directory(method.folder, error)) {
      throw InputError(method.folder + ": no such folder of saliency maps");
    }
    const fs::path scanpath = fs::path(method.folder) / "scanpath.json";
    if (fs::exists(scanpath, error)) {
      std::ifstream file(scanpath);
      try {
        method.scanpaths = nlohmann::json::parse(file);
      } catch (const std::exception& e) {
        throw InputError(scanpath.string() + ": not valid JSON: " + e.what());
      }
    }
    methods.push_back(std::move(method));
  }
  for (const std::string& name : request.baselines) {
    if (std::find(BaselineNames().begin(), BaselineNames().end(), name) == BaselineNames().end()) {
      throw ConfigError("--baselines " + name +
                        ": not one of centre, spectral_residual, fine_grained");
    }
    Method method;
    method.name = name;
    methods.push_back(std::move(method));
  }
  if (methods.empty()) throw ConfigError("eval-fixations: give MAPS folders or --baselines");
  for (Method& method : methods) {
    method.values.assign(FixationMetricNames().size(), {});
    method.scanpath_shares.assign(kScanpathDepth, {});
  }
  return methods;
}

// An image at its scored size and its fixations in the scored coordinates.
struct Loaded {
  cv::Mat stimulus;
  std::vector<Fixation> fixations;
  double scale = 1.0;
  cv::Size native;  // the stimulus's own size
};

// Empty, or the reason when the stimulus cannot be used.
std::string LoadStimulus(const FixationItem& item, int max_side, Loaded* loaded) {
  cv::Mat bgr;
  try {
    bgr = ReadImageFile(item.stimulus_path, cv::IMREAD_COLOR, item.stimulus_path);
  } catch (const InputError& e) {
    return e.what();
  }
  loaded->native = bgr.size();
  loaded->scale = ScoringScale(bgr.size(), max_side);
  loaded->stimulus =
      ToSize(bgr, cv::Size(static_cast<int>(std::lround(bgr.cols * loaded->scale)),
                           static_cast<int>(std::lround(bgr.rows * loaded->scale))));
  for (Fixation f : ReadFixationFile(item.fixations_path)) {
    f.x *= loaded->scale;
    f.y *= loaded->scale;
    loaded->fixations.push_back(f);
  }
  return "";
}

// Every image's fixations as shares of its width and height (x / w, y / h), for the shuffled
// AUC's negatives: a cheap first pass, fixations only.
std::vector<std::vector<Fixation>> NormalisedFixations(const std::vector<FixationItem>& items) {
  std::vector<std::vector<Fixation>> normalised(items.size());
  for (size_t i = 0; i < items.size(); ++i) {
    const cv::Size size = [&] {
      // The header alone would do; the decoder reads the whole image, once more later.
      const cv::Mat bgr = cvextra::Get("eval-fixations")
                              .Read(items[i].stimulus_path, cv::IMREAD_REDUCED_GRAYSCALE_8);
      return bgr.empty() ? cv::Size() : cv::Size(bgr.cols * 8, bgr.rows * 8);
    }();
    if (size.area() == 0) continue;
    for (const Fixation& f : ReadFixationFile(items[i].fixations_path)) {
      normalised[i].push_back({f.subject, f.x / size.width, f.y / size.height});
    }
  }
  return normalised;
}

// The map of `method` for `item` at the scored size (a baseline's computed, a folder's read and
// resized), and the method's scanpath shares on it.
cv::Mat MapOf(const FixationItem& item, const Loaded& loaded, const EvalFixationsRequest& request,
              const FixationEvaluationObserver& observer, Method* method) {
  if (method->folder.empty()) {
    return BaselineMap(method->name, loaded.stimulus, request.baseline_blur);
  }
  const cv::Size size = loaded.stimulus.size();
  const fs::path path = fs::path(method->folder) / (item.id + ".pfm");
  std::error_code error;
  if (!fs::exists(path, error))
    throw InputError(path.string() + ": no saliency map for image " + item.id);
  cv::Mat map = ReadPfmOneChannel(path.string(), "a saliency map");
  const cv::Size& native = loaded.native;
  if (map.size() != native && map.size() != size && observer.on_note) {
    observer.on_note(path.string() + " is " + std::to_string(map.cols) + "x" +
                     std::to_string(map.rows) + ", its stimulus " + std::to_string(native.width) +
                     "x" + std::to_string(native.height) + ": resized");
  }
  map = ToSize(map, size);
  if (method->scanpaths.is_object() && method->scanpaths.contains(item.id)) {
    const std::vector<double> shares =
        ScanpathShares(method->scanpaths.at(item.id), loaded.scale, loaded.fixations);
    for (int k = 0; k < kScanpathDepth; ++k) method->scanpath_shares[k].push_back(shares[k]);
  }
  return map;
}

// Scores image `i` for every method.
void ScoreImage(size_t i, const std::vector<FixationItem>& items,
                const std::vector<std::vector<Fixation>>& normalised, const Loaded& loaded,
                const EvalFixationsRequest& request, const FixationEvaluationObserver& observer,
                std::vector<Method>* methods) {
  const cv::Size size = loaded.stimulus.size();
  std::vector<Fixation> others;
  for (size_t j = 0; j < items.size(); ++j) {
    if (j == i) continue;
    for (const Fixation& f : normalised[j]) {
      others.push_back({f.subject, f.x * size.width, f.y * size.height});
    }
  }
  const double sigma =
      request.sigma > 0.0 ? request.sigma : 0.025 * std::max(size.width, size.height);
  const cv::Mat density = FixationDensity(size, loaded.fixations, sigma);
  const cv::Mat centre = CentreBias(size);
  for (Method& method : *methods) {
    const cv::Mat map = MapOf(items[i], loaded, request, observer, &method);
    const FixationScores scores = ScoreMap(map, loaded.fixations, others, density, centre);
    for (size_t m = 0; m < FixationMetricNames().size(); ++m) {
      method.values[m].push_back(Get(scores, FixationMetricNames()[m]));
    }
    method.ids.push_back(items[i].id);
  }
}

// The mean scanpath share of each depth k = 1..kScanpathDepth.
std::vector<double> MeanShares(const Method& method) {
  std::vector<double> shares;
  for (int k = 0; k < kScanpathDepth; ++k) {
    shares.push_back(MeanWithInterval(method.scanpath_shares[k]).mean);
  }
  return shares;
}

// Each method's means with their 95 % intervals, by name.
nlohmann::json MeansJson(const std::vector<Method>& methods) {
  nlohmann::json means = nlohmann::json::object();
  for (const Method& method : methods) {
    nlohmann::json entry = {{"images", method.ids.size()},
                            {"maps", method.folder.empty() ? "baseline" : method.folder}};
    for (size_t m = 0; m < FixationMetricNames().size(); ++m) {
      const MeanInterval v = MeanWithInterval(method.values[m]);
      entry[FixationMetricNames()[m]] = {{"mean", v.mean}, {"ci95", {v.low, v.high}}};
    }
    if (!method.scanpath_shares[0].empty()) {
      entry["scanpath_fixation_share"] = MeanShares(method);  // k = 1..5
    }
    means[method.name] = entry;
  }
  return means;
}

// OUT/METHOD.csv (a row an image) and OUT/fixations.json.
void WriteReport(const EvalFixationsRequest& request, const FixationDataset& dataset,
                 const std::vector<std::string>& failed, const std::vector<Method>& methods) {
  const fs::path out(request.out);
  std::error_code error;
  fs::create_directories(out, error);
  if (error) throw InputError(out.string() + ": cannot create the folder: " + error.message());
  for (const Method& method : methods) {
    const fs::path csv_path = out / (method.name + ".csv");
    std::ofstream csv(csv_path);
    csv << "id";
    for (const std::string& metric : FixationMetricNames()) csv << "," << metric;
    csv << "\n" << std::setprecision(6);
    for (size_t r = 0; r < method.ids.size(); ++r) {
      csv << method.ids[r];
      for (const std::vector<double>& values : method.values) csv << "," << values[r];
      csv << "\n";
    }
    if (!csv) throw InputError(csv_path.string() + ": cannot be written");
  }
  const nlohmann::json report = {{"dataset", request.dataset},
                                 {"skipped", dataset.skipped},
                                 {"failed", failed},
                                 {"skip", request.skip},
                                 {"first", request.first},
                                 {"max_side", request.max_side},
                                 {"sigma_px", request.sigma},
                                 {"baseline_blur", request.baseline_blur},
                                 {"command", request.command_line},
                                 {"methods", MeansJson(methods)}};
  const fs::path json_path = out / "fixations.json";
  std::ofstream file(json_path);
  file << JsonText(report, 2) << "\n";
  if (!file) throw InputError(json_path.string() + ": cannot be written");
}

}  // namespace

FixationEvaluation EvaluateFixations(const EvalFixationsRequest& request,
                                     const FixationEvaluationObserver& observer) {
  const FixationDataset dataset = OpenFixationDataset(request.dataset);
  std::vector<FixationItem> items = dataset.items;
  items.erase(items.begin(), items.begin() + std::min<size_t>(request.skip, items.size()));
  if (request.first > 0 && static_cast<int>(items.size()) > request.first)
    items.resize(request.first);
  std::vector<Method> methods = MethodsOf(request);
  const std::vector<std::vector<Fixation>> normalised = NormalisedFixations(items);
  std::vector<std::string> failed;
  for (size_t i = 0; i < items.size(); ++i) {
    Loaded loaded;
    const std::string error = LoadStimulus(items[i], request.max_side, &loaded);
    if (!error.empty()) {
      if (observer.on_unreadable) observer.on_unreadable(error);
      failed.push_back(items[i].stimulus_path);
      continue;
    }
    ScoreImage(i, items, normalised, loaded, request, observer, &methods);
    if ((i + 1) % 50 == 0 && observer.on_progress) {
      observer.on_progress(static_cast<int>(i + 1), static_cast<int>(items.size()));
    }
  }
  if (!request.out.empty()) WriteReport(request, dataset, failed, methods);
  FixationEvaluation result;
  result.table = Table(methods);
  result.failed = failed;
  for (const Method& method : methods) {
    if (!method.scanpath_shares[0].empty()) {
      result.scanpath_shares.emplace_back(method.name, MeanShares(method));
    }
  }
  return result;
}

}  // namespace attend
