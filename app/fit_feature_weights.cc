#include "app/fit_feature_weights.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "eval/fixation_data.h"
#include "io/image_file.h"
#include "pipeline/options_io.h"
#include "pipeline/still_saliency.h"
#include "util/error.h"

namespace attend {

FitWeightsResult FitFeatureWeights(const FitWeightsRequest& request) {
  const std::string& config_path = request.config_path;
  AttendOptions options = request.options;
  const FixationDataset dataset = OpenFixationDataset(request.dataset);
  std::vector<FixationItem> items = dataset.items;
  if (static_cast<int>(items.size()) > request.train) items.resize(request.train);
  const StillSaliency still(options, request.home);

  std::vector<FitSample> samples;
  std::vector<std::string> names;
  for (const FixationItem& item : items) {
    const cv::Mat bgr = ReadImageFile(item.stimulus_path, cv::IMREAD_COLOR, item.stimulus_path);
    const StillMaps maps = still.Compute(bgr, true, 0);
    names = maps.feature_names;
    const int side = std::max(bgr.cols, bgr.rows);
    const double scale =
        side > request.max_side ? static_cast<double>(request.max_side) / side : 1.0;
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
  fit_options.step = request.step;
  for (const std::string& name : names) {
    for (const FeatureSpec& spec : options.features) {
      if (spec.name == name) fit_options.additive.push_back(spec.additive);
    }
  }
  const WeightFit fit = FitWeights(samples, fit_options);
  for (FeatureSpec& spec : options.features) {
    const auto at = std::find(names.begin(), names.end(), spec.name);
    if (spec.enabled && at != names.end()) spec.weight = fit.weights[at - names.begin()];
  }
  {
    std::ofstream file(request.out);
    file << "# attend fit-weights --dataset " << request.dataset << " --config " << config_path
         << " --train " << request.train << " --step " << request.step << " --max-side "
         << request.max_side << "\n# images 1.." << items.size()
         << " by id were used for fitting: score on the others (--skip " << items.size() << ")\n"
         << OptionsToYaml(options) << "\n";
    if (!file) throw InputError(request.out + ": cannot be written");
  }
  return {names, fit, static_cast<int>(items.size())};
}

}  // namespace attend
