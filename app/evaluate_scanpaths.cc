#include "app/evaluate_scanpaths.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>
#include <system_error>

#include "app/scanpath_inputs.h"
#include "eval/fixation_metrics.h"
#include "eval/scanpath_baselines.h"
#include "io/pfm.h"
#include "util/error.h"
#include "util/json_text.h"

namespace attend {

namespace {

namespace fs = std::filesystem;

constexpr size_t kPathMeasures = 7;
using PathScores = std::array<double, kPathMeasures>;  // in the order of ScanpathMeasureNames()
constexpr double kNoScore = std::numeric_limits<double>::quiet_NaN();

enum class MethodKind { kModel, kPeaks, kCentre, kHuman };

struct ScanpathMethod {
  std::string name;
  MethodKind kind = MethodKind::kModel;
  int model = -1;  // the model folder of kModel and kPeaks
  std::vector<std::string> ids;
  std::vector<PathScores> per_image;  // NaN where a measure has no value on that image
};

// What every comparison of the run shares.
struct PathSetting {
  ScanMatchOptions scanmatch;
  MultiMatchOptions multimatch;
  int length = 8;
  double duration_s = -1.0;  // the models' and baselines' fixations
};

PathScores ComparePaths(const Scanpath& a, const Scanpath& b, cv::Size size, const PathSetting& setting) {
  PathScores scores;
  scores.fill(kNoScore);
  scores[0] = ScanMatch(a, b, size, setting.scanmatch);
  scores[1] = SequenceScore(a, b, size, setting.scanmatch.grid);
  if (const std::optional<MultiMatchScores> mm = MultiMatch(a, b, size, setting.multimatch)) {
    scores[2] = mm->shape;
    scores[3] = mm->direction;
    scores[4] = mm->length;
    scores[5] = mm->position;
    scores[6] = mm->duration;
  }
  return scores;
}

// Each measure's mean over `list`, leaving out NaNs (NaN when all are).
PathScores MeanPathScores(const std::vector<PathScores>& list) {
  PathScores mean;
  for (size_t m = 0; m < kPathMeasures; ++m) {
    double sum = 0.0;
    int n = 0;
    for (const PathScores& s : list) {
      if (std::isnan(s[m])) continue;
      sum += s[m];
      ++n;
    }
    mean[m] = n > 0 ? sum / n : kNoScore;
  }
  return mean;
}

// `path` against every observer of the image: the mean over observers.
PathScores AgainstObservers(const Scanpath& path, const ObservedImage& image,
                        const PathSetting& setting) {
  std::vector<PathScores> list;
  for (const Scanpath& observer : image.observers) {
    list.push_back(ComparePaths(path, observer, image.size, setting));
  }
  return MeanPathScores(list);
}

// Every observer against every other (each pair once: the measures are symmetric up to ties
// in the alignments): the mean over pairs, which is the mean over observers of each one's
// mean against the others.
PathScores HumanCeiling(const ObservedImage& image, const PathSetting& setting) {
  std::vector<PathScores> list;
  for (size_t i = 0; i < image.observers.size(); ++i) {
    for (size_t j = i + 1; j < image.observers.size(); ++j) {
      list.push_back(ComparePaths(image.observers[i], image.observers[j], image.size, setting));
    }
  }
  if (list.empty()) {
    PathScores none;
    none.fill(kNoScore);
    return none;
  }
  return MeanPathScores(list);
}

// A draw of each image's centre scanpaths depends on the seed and the image's id only, so
// that a split scores the same draws as the whole dataset.
uint64_t ImageSeed(uint64_t seed, const std::string& id) {
  uint64_t hash = 14695981039346656037ull;  // FNV-1a
  for (const unsigned char c : id) hash = (hash ^ c) * 1099511628211ull;
  return seed ^ hash;
}

PathScores CentreScores(const ObservedImage& image, const EvalScanpathsRequest& request,
                    const PathSetting& setting) {
  cv::RNG rng(ImageSeed(request.seed, image.id));
  std::vector<PathScores> draws;
  for (int d = 0; d < request.centre_draws; ++d) {
    const Scanpath path = CentreBiasScanpath(image.size, setting.length, setting.duration_s, &rng);
    draws.push_back(AgainstObservers(path, image, setting));
  }
  return MeanPathScores(draws);
}

PathScores PeakScores(const ModelScanpaths& model, const ObservedImage& image,
                  const EvalScanpathsRequest& request, const PathSetting& setting) {
  const fs::path map_path = fs::path(model.folder) / (image.id + ".pfm");
  std::error_code error;
  if (!fs::exists(map_path, error)) {
    throw InputError(map_path.string() + ": no saliency map for image " + image.id +
                     " (--baselines peaks reads each folder's maps)");
  }
  const cv::Mat map = ReadPfmOneChannel(map_path.string(), "a saliency map");
  const Scanpath path = SaliencyPeaks(map, image.size, setting.length, request.peak_separation,
                                      setting.duration_s);
  return AgainstObservers(path, image, setting);
}

bool Lists(const std::vector<std::string>& list, const std::string& name) {
  return std::find(list.begin(), list.end(), name) != list.end();
}

std::vector<ScanpathMethod> ScanpathMethodsOf(const EvalScanpathsRequest& request,
                                      const std::vector<ModelScanpaths>& models) {
  std::vector<ScanpathMethod> methods;
  for (size_t m = 0; m < models.size(); ++m) {
    methods.push_back({models[m].name, MethodKind::kModel, static_cast<int>(m), {}, {}});
  }
  if (Lists(request.baselines, "peaks")) {
    for (size_t m = 0; m < models.size(); ++m) {
      methods.push_back({models[m].name + "_peaks", MethodKind::kPeaks, static_cast<int>(m), {}, {}});
    }
  }
  if (Lists(request.baselines, "centre")) methods.push_back({"centre", MethodKind::kCentre, -1, {}, {}});
  if (Lists(request.baselines, "human")) methods.push_back({"human", MethodKind::kHuman, -1, {}, {}});
  return methods;
}

void CheckScanpathRequest(const EvalScanpathsRequest& request) {
  for (const std::string& name : request.baselines) {
    if (!Lists(ScanpathBaselineNames(), name)) {
      throw ConfigError("--baselines " + name + ": not one of human, centre, peaks");
    }
  }
  if (request.maps.empty() && request.baselines.empty()) {
    throw ConfigError("eval-scanpaths: give MAPS folders or --baselines");
  }
  if (request.maps.empty() && Lists(request.baselines, "peaks")) {
    throw ConfigError("--baselines peaks: needs MAPS folders (their saliency maps' peaks)");
  }
  if (request.length < 1) throw ConfigError("--length: must be at least 1");
  if (request.centre_draws < 1) throw ConfigError("--centre-draws: must be at least 1");
  if (!(request.scanmatch_threshold >= 0.0)) {
    throw ConfigError("--scanmatch-threshold: must be >= 0 (0: from the data)");
  }
  std::string error;
  ScanMatchOptions scanmatch = request.scanmatch;
  scanmatch.threshold = 1.0;  // the threshold is checked once it is known
  if (!scanmatch.Check(&error)) throw ConfigError("ScanMatch " + error);
  if (!request.multimatch.Check(&error)) throw ConfigError("MultiMatch " + error);
}

// The items of the split (--skip, then --first), read; images without any observer left are
// left out with a note.
std::vector<ObservedImage> ReadObservedImages(const EvalScanpathsRequest& request,
                                      const ScanpathEvaluationObserver& observer) {
  std::vector<FixationItem> items = OpenFixationDataset(request.dataset).items;
  items.erase(items.begin(), items.begin() + std::min<size_t>(request.skip, items.size()));
  if (request.first > 0 && static_cast<int>(items.size()) > request.first) {
    items.resize(request.first);
  }
  const ObserverReading reading{request.length, request.drop_first, request.durations};
  std::vector<ObservedImage> images;
  for (const FixationItem& item : items) {
    ObservedImage image = ReadObservedImage(item, reading);
    if (image.observers.empty()) {
      if (observer.on_note) {
        observer.on_note(item.fixations_path + ": no observer has a fixation to compare: left out");
      }
      continue;
    }
    images.push_back(std::move(image));
  }
  if (images.empty()) throw InputError(request.dataset + ": no image of the split has observers");
  return images;
}

// The ScanMatch threshold: the request's, or 2 sd of the compared observers' saccade amplitudes.
double ScanMatchThresholdOf(const EvalScanpathsRequest& request, const std::vector<ObservedImage>& images) {
  if (request.scanmatch_threshold > 0.0) return request.scanmatch_threshold;
  std::vector<double> amplitudes;
  for (const ObservedImage& image : images) {
    for (const Scanpath& path : image.observers) {
      const std::vector<double> a = SaccadeAmplitudesInCells(path, image.size, request.scanmatch.grid);
      amplitudes.insert(amplitudes.end(), a.begin(), a.end());
    }
  }
  if (amplitudes.size() < 2) {
    throw InputError(request.dataset +
                     ": too few saccades to set the ScanMatch threshold; give --scanmatch-threshold");
  }
  const double threshold = ScanMatchThreshold(amplitudes);
  if (!(threshold > 0.0)) {
    throw InputError(request.dataset + ": every saccade has the same amplitude, so the ScanMatch "
                     "threshold (2 sd) is 0; give --scanmatch-threshold");
  }
  return threshold;
}

// The median of the observers' fixation durations over the scored images; -1 when the files
// give none.
double MedianFixationDuration(const std::vector<ObservedImage>& images) {
  std::vector<double> all;
  for (const ObservedImage& image : images) {
    all.insert(all.end(), image.durations_s.begin(), image.durations_s.end());
  }
  if (all.empty()) return -1.0;
  std::sort(all.begin(), all.end());
  const size_t middle = all.size() / 2;
  return all.size() % 2 == 1 ? all[middle] : 0.5 * (all[middle - 1] + all[middle]);
}

PathScores ScoreMethod(const ScanpathMethod& method, size_t image_index,
                   const std::vector<ObservedImage>& images,
                   const std::vector<ModelScanpaths>& models,
                   const std::vector<std::vector<Scanpath>>& model_paths,
                   const EvalScanpathsRequest& request, const PathSetting& setting) {
  const ObservedImage& image = images[image_index];
  switch (method.kind) {
    case MethodKind::kModel: {
      const Scanpath& path = model_paths[method.model][image_index];
      if (path.empty()) {  // only with --empty-scanpath zero
        PathScores zero;
        zero.fill(0.0);
        return zero;
      }
      return AgainstObservers(path, image, setting);
    }
    case MethodKind::kPeaks:
      return PeakScores(models[method.model], image, request, setting);
    case MethodKind::kCentre:
      return CentreScores(image, request, setting);
    case MethodKind::kHuman:
      return HumanCeiling(image, setting);
  }
  throw InternalError("unknown scanpath method");
}

// The values of measure `m` of `method` that exist, one per image.
std::vector<double> MeasureValues(const ScanpathMethod& method, size_t m) {
  std::vector<double> values;
  for (const PathScores& s : method.per_image) {
    if (!std::isnan(s[m])) values.push_back(s[m]);
  }
  return values;
}

std::string ScanpathTable(const std::vector<ScanpathMethod>& methods) {
  std::ostringstream out;
  out << std::fixed << std::setprecision(3);
  out << "| method | images | ScanMatch | sequence | MM shape | MM direction | MM length | "
         "MM position | MM duration |\n|---|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const ScanpathMethod& method : methods) {
    out << "| " << method.name << " | " << MeasureValues(method, 0).size() << " |";
    for (size_t m = 0; m < kPathMeasures; ++m) {
      const std::vector<double> values = MeasureValues(method, m);
      if (values.empty()) {
        out << " n/a |";
        continue;
      }
      const MeanInterval v = MeanWithInterval(values);
      out << " " << v.mean << " +- " << (v.high - v.mean) << " |";
    }
    out << "\n";
  }
  return out.str();
}

const char* PathKindName(MethodKind kind) {
  switch (kind) {
    case MethodKind::kModel:
      return "scanpath.json";
    case MethodKind::kPeaks:
      return "saliency peaks";
    case MethodKind::kCentre:
      return "centre bias draws";
    case MethodKind::kHuman:
      return "other observers";
  }
  return "";
}

nlohmann::json PathMethodsJson(const std::vector<ScanpathMethod>& methods,
                           const std::vector<ModelScanpaths>& models,
                           const std::vector<std::vector<Scanpath>>& model_paths) {
  nlohmann::json all = nlohmann::json::object();
  for (const ScanpathMethod& method : methods) {
    nlohmann::json entry = {{"kind", PathKindName(method.kind)}};
    if (method.model >= 0) entry["maps"] = models[method.model].folder;
    if (method.kind == MethodKind::kModel) {
      const std::vector<Scanpath>& paths = model_paths[method.model];
      entry["empty_scanpaths"] = std::count_if(paths.begin(), paths.end(),
                                               [](const Scanpath& p) { return p.empty(); });
    }
    for (size_t m = 0; m < kPathMeasures; ++m) {
      const std::vector<double> values = MeasureValues(method, m);
      nlohmann::json measure = {{"n", values.size()}, {"mean", nullptr}, {"ci95", nullptr}};
      if (!values.empty()) {
        const MeanInterval v = MeanWithInterval(values);
        measure["mean"] = v.mean;
        measure["ci95"] = {v.low, v.high};
      }
      entry[ScanpathMeasureNames()[m]] = measure;
    }
    all[method.name] = entry;
  }
  return all;
}

nlohmann::json PathOptionsJson(const EvalScanpathsRequest& request, const PathSetting& setting) {
  return {{"length", request.length},
          {"drop_first", request.drop_first},
          {"grid", {setting.scanmatch.grid.columns, setting.scanmatch.grid.rows}},
          {"scanmatch_threshold_cells", setting.scanmatch.threshold},
          {"scanmatch_threshold_from_data", !(request.scanmatch_threshold > 0.0)},
          {"scanmatch_gap", setting.scanmatch.gap},
          {"scanmatch_bin_ms", setting.scanmatch.temporal_bin_s * 1000.0},
          {"multimatch_simplify", setting.multimatch.simplify},
          {"multimatch_amplitude_threshold", setting.multimatch.amplitude_threshold},
          {"multimatch_direction_threshold_deg", setting.multimatch.direction_threshold_deg},
          {"multimatch_duration_threshold_s", setting.multimatch.duration_threshold_s},
          {"model_duration_s",
           setting.duration_s >= 0.0 ? nlohmann::json(setting.duration_s) : nlohmann::json()},
          {"centre_draws", request.centre_draws},
          {"seed", request.seed},
          {"peak_separation", request.peak_separation},
          {"empty_scanpath", request.empty_scores_zero ? "zero" : "error"}};
}

void WriteScanpathReport(const EvalScanpathsRequest& request, const PathSetting& setting,
                 const std::vector<ObservedImage>& images,
                 const std::vector<ModelScanpaths>& models,
                 const std::vector<std::vector<Scanpath>>& model_paths,
                 const std::vector<ScanpathMethod>& methods) {
  const fs::path out(request.out);
  std::error_code error;
  fs::create_directories(out, error);
  if (error) throw OutputError(out.string() + ": cannot create the folder: " + error.message());
  for (const ScanpathMethod& method : methods) {
    const fs::path csv_path = out / (method.name + ".csv");
    std::ofstream csv(csv_path);
    csv << "id,observers";
    for (const std::string& name : ScanpathMeasureNames()) csv << "," << name;
    csv << "\n" << std::setprecision(6);
    for (size_t r = 0; r < method.ids.size(); ++r) {
      csv << method.ids[r] << "," << images[r].observers.size();
      for (const double value : method.per_image[r]) {
        csv << ",";
        if (!std::isnan(value)) csv << value;
      }
      csv << "\n";
    }
    if (!csv) throw OutputError(csv_path.string() + ": cannot be written");
  }
  int left_out = 0, outside = 0;
  for (const ObservedImage& image : images) {
    left_out += image.observers_left_out;
    outside += image.fixations_outside;
  }
  const nlohmann::json report = {{"dataset", request.dataset},
                                 {"skip", request.skip},
                                 {"first", request.first},
                                 {"images", images.size()},
                                 {"observers_left_out", left_out},
                                 {"fixations_outside_left_out", outside},
                                 {"options", PathOptionsJson(request, setting)},
                                 {"command", request.command_line},
                                 {"methods", PathMethodsJson(methods, models, model_paths)}};
  const fs::path json_path = out / "scanpaths.json";
  std::ofstream file(json_path);
  file << JsonText(report, 2) << "\n";
  if (!file) throw OutputError(json_path.string() + ": cannot be written");
}

// Temporal bins need every compared fixation's duration.
void CheckDurations(const std::vector<ObservedImage>& images, const PathSetting& setting,
                    const std::string& dataset) {
  if (setting.scanmatch.temporal_bin_s <= 0.0) return;
  if (setting.duration_s < 0.0) {
    throw ConfigError("--scanmatch-bin-ms: " + dataset +
                      "'s fixation files give no durations (see --duration-column)");
  }
  for (const ObservedImage& image : images) {
    for (const Scanpath& path : image.observers) {
      for (const Fixation& f : path) {
        if (f.duration_s < 0.0) {
          throw InputError(dataset + ": image " + image.id +
                           ": its fixation file gives no durations, which --scanmatch-bin-ms needs");
        }
      }
    }
  }
}

}  // namespace

ScanpathEvaluation EvaluateScanpaths(const EvalScanpathsRequest& request,
                                     const ScanpathEvaluationObserver& observer) {
  CheckScanpathRequest(request);
  std::vector<ModelScanpaths> models;
  for (const std::string& spec : request.maps) models.push_back(ReadModelScanpaths(spec));
  const std::vector<ObservedImage> images = ReadObservedImages(request, observer);
  PathSetting setting;
  setting.length = request.length;
  setting.scanmatch = request.scanmatch;
  setting.multimatch = request.multimatch;
  setting.duration_s = MedianFixationDuration(images);  // what attend uses: docs/FIXATIONS.md
  CheckDurations(images, setting, request.dataset);
  setting.scanmatch.threshold = ScanMatchThresholdOf(request, images);
  // Every model's scanpaths are read and checked before anything is scored.
  std::vector<std::vector<Scanpath>> model_paths(models.size());
  for (size_t m = 0; m < models.size(); ++m) {
    for (const ObservedImage& image : images) {
      model_paths[m].push_back(
          ModelScanpath(models[m], image.id, request.length, setting.duration_s,
                        request.empty_scores_zero));
    }
  }
  std::vector<ScanpathMethod> methods = ScanpathMethodsOf(request, models);
  for (size_t i = 0; i < images.size(); ++i) {
    for (ScanpathMethod& method : methods) {
      method.per_image.push_back(
          ScoreMethod(method, i, images, models, model_paths, request, setting));
      method.ids.push_back(images[i].id);
    }
    if ((i + 1) % 50 == 0 && observer.on_progress) {
      observer.on_progress(static_cast<int>(i + 1), static_cast<int>(images.size()));
    }
  }
  if (!request.out.empty()) WriteScanpathReport(request, setting, images, models, model_paths, methods);
  ScanpathEvaluation result;
  result.table = ScanpathTable(methods);
  result.threshold_cells = setting.scanmatch.threshold;
  result.model_duration_s = setting.duration_s;
  result.images = static_cast<int>(images.size());
  return result;
}

const std::vector<std::string>& ScanpathBaselineNames() {
  static const std::vector<std::string> names = {"human", "centre", "peaks"};
  return names;
}

const std::vector<std::string>& ScanpathMeasureNames() {
  static const std::vector<std::string> names = {"scanmatch",    "sequence",  "mm_shape",
                                                 "mm_direction", "mm_length", "mm_position",
                                                 "mm_duration"};
  return names;
}

}  // namespace attend
