#include "saliency/saliency.h"

#include <opencv2/imgproc.hpp>

#include "saliency/normalisation.h"
#include "util/enum_table.h"
#include "util/error.h"

namespace attend {

const std::vector<std::string>& SaliencyOptions::Normalisations() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> built_in;
    for (const BuiltinNormalisation& row : BuiltinNormalisations()) built_in.push_back(row.name);
    return built_in;
  }();
  return names;
}

namespace {

constexpr EnumTable<SaliencyCombination, 2> kCombinations = {{{
    {SaliencyCombination::kSum, "sum"},
    {SaliencyCombination::kProduct, "product"},
}}};

}  // namespace

const OptionFields<SaliencyOptions>& SaliencyOptions::Fields() {
  using O = SaliencyOptions;
  static const OptionFields<SaliencyOptions> fields = {
      {"normalisation", &O::normalisation,
       "each feature's normalisation unless it names its own: a built-in one "
       "(saliency/normalisation.h) or a plugin's"},
      {"local_maxima_window", &O::local_maxima_window, Range::Closed(3, 1001),
       "local_maxima: the odd window side, px"},
      {"blur", &O::blur, Range::Closed(0, 1),
       "the combined map's Gaussian blur, a share of the image's larger side; 0: none"},
      {"combination", EnumField<&O::combination, kCombinations>(),
       "sum: the weighted mean (the thesis); product: the weighted geometric mean"},
      {"gamma", &O::gamma, Range::Closed(0.1, 10),
       "the combined (and blurred) map, scaled to a maximum of 1, to this power; 1: as it is"}};
  return fields;
}

std::string SaliencyOptions::Check() const {
  const std::string error = CheckFieldRanges(*this, Fields());
  if (!error.empty()) return error;
  if (local_maxima_window % 2 == 0) return "local_maxima_window must be odd";
  return "";
}

void NormaliseMap(const cv::Mat& map, const SaliencyOptions& options, cv::Mat* out) {
  const std::vector<BuiltinNormalisation>& table = BuiltinNormalisations();
  // A name that is not built in (a plugin's, which the registry applies) normalises as minmax,
  // the first row.
  const BuiltinNormalisation* chosen = &table.front();
  for (const BuiltinNormalisation& row : table) {
    if (options.normalisation == row.name) chosen = &row;
  }
  chosen->normalise(map, options, out);
}

void CombineMaps(const std::vector<cv::Mat>& normalised, const std::vector<double>& weights,
                 cv::Size size, cv::Mat* out) {
  ATTEND_CHECK(normalised.size() == weights.size()) << "one weight per map";
  out->create(size, CV_32FC1);
  out->setTo(0.f);
  double total = 0.0;
  for (const double weight : weights) total += weight;
  if (!(total > 0.0)) return;
  for (size_t i = 0; i < normalised.size(); ++i) {
    if (weights[i] == 0.0) continue;
    cv::scaleAdd(normalised[i], static_cast<float>(weights[i] / total), *out, *out);
  }
}

void MultiplyMaps(const std::vector<cv::Mat>& normalised, const std::vector<double>& weights,
                  const std::vector<bool>& additive, cv::Size size, cv::Mat* out) {
  ATTEND_CHECK(normalised.size() == weights.size()) << "one weight per map";
  ATTEND_CHECK(additive.empty() || additive.size() == weights.size()) << "one flag per map";
  constexpr double kFloor = 0.01;  // so that a 0 somewhere is a strong veto, not -infinity
  const auto is_added = [&additive](size_t i) { return !additive.empty() && additive[i]; };
  out->create(size, CV_32FC1);
  out->setTo(0.f);
  double total = 0.0, factors = 0.0;
  for (size_t i = 0; i < weights.size(); ++i) {
    total += weights[i];
    if (!is_added(i)) factors += weights[i];
  }
  if (!(total > 0.0)) return;
  if (factors > 0.0) {
    cv::Mat logs;
    for (size_t i = 0; i < normalised.size(); ++i) {
      if (weights[i] == 0.0 || is_added(i)) continue;
      cv::log(normalised[i] + kFloor, logs);
      cv::scaleAdd(logs, static_cast<float>(weights[i] / factors), *out, *out);
    }
    cv::exp(*out, *out);
    // From [kFloor, 1 + kFloor] to [0, 1].
    *out = (*out - kFloor) / 1.0;
    cv::max(*out, 0.0, *out);
    cv::min(*out, 1.0, *out);
    *out *= factors / total;
  }
  for (size_t i = 0; i < normalised.size(); ++i) {
    if (weights[i] == 0.0 || !is_added(i)) continue;
    cv::scaleAdd(normalised[i], static_cast<float>(weights[i] / total), *out, *out);
  }
}

namespace {

// A Gaussian of `blur` times the map's larger side, then scaled back to its maximum.
void BlurSaliency(double blur, cv::Mat* map) {
  double low = 0.0, high = 0.0;
  cv::minMaxLoc(*map, &low, &high);
  const double sigma = blur * std::max(map->cols, map->rows);
  cv::GaussianBlur(*map, *map, cv::Size(), sigma, sigma, cv::BORDER_REPLICATE);
  double blurred_high = 0.0;
  cv::minMaxLoc(*map, nullptr, &blurred_high);
  if (blurred_high > 0.0) *map *= high / blurred_high;
}

}  // namespace

void SmoothSaliency(const SaliencyOptions& options, cv::Mat* map) {
  if (map->empty()) return;
  if (options.blur > 0.0) BlurSaliency(options.blur, map);
  // Scaled to a maximum of 1 first, so that the power shapes the map the same on every image
  // (a map whose maximum is 0.3 would otherwise fall to 0.027 at gamma 3, under every absolute
  // threshold of the attention stage); it stays in [0, 1] and keeps its order.
  if (options.gamma != 1.0) {
    double high = 0.0;
    cv::minMaxLoc(*map, nullptr, &high);
    if (high > 0.0) *map /= high;
    cv::pow(*map, options.gamma, *map);
  }
}


}  // namespace attend
