#include "saliency/saliency.h"

#include <opencv2/imgproc.hpp>

#include "util/enum_table.h"
#include "util/error.h"

namespace attend {

namespace {

// (1 - m)^2, m the mean value of the local maxima of `unit` (a [0, 1] map whose maximum is 1)
// other than one plateau at the global maximum.
float LocalMaximaFactor(const cv::Mat& unit, int window) {
  cv::Mat dilated;
  cv::dilate(unit, dilated, cv::getStructuringElement(cv::MORPH_RECT, cv::Size(window, window)));
  cv::Mat is_peak = unit == dilated;
  // A plateau of zeros is not a peak: it is where the map has nothing.
  is_peak &= unit > 0.f;
  cv::Mat plateaus;
  const int count = cv::connectedComponents(is_peak, plateaus, 8, CV_32S);
  // Pixels of one plateau all equal: each equals the maximum of a window holding its
  // neighbour, and the other way round. Take one value per plateau.
  std::vector<float> values(count, -1.f);
  for (int y = 0; y < unit.rows; ++y) {
    const int* plateau = plateaus.ptr<int>(y);
    const float* value = unit.ptr<float>(y);
    for (int x = 0; x < unit.cols; ++x) {
      if (plateau[x] > 0) values[plateau[x]] = value[x];
    }
  }
  bool global_skipped = false;
  double sum = 0.0;
  int others = 0;
  for (int i = 1; i < count; ++i) {
    if (!global_skipped && values[i] >= 1.f) {
      global_skipped = true;
      continue;
    }
    sum += values[i];
    ++others;
  }
  const double mean = others > 0 ? sum / others : 0.0;
  return static_cast<float>((1.0 - mean) * (1.0 - mean));
}

}  // namespace

const std::vector<std::string>& SaliencyOptions::Normalisations() {
  static const std::vector<std::string> names = {"minmax", "local_maxima"};
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
       "each feature's normalisation unless it names its own: minmax, local_maxima or a "
       "plugin's"},
      {"local_maxima_window", &O::local_maxima_window, Range::Closed(3, 1001),
       "local_maxima: the odd window side, px"},
      {"blur", &O::blur, Range::Closed(0, 1),
       "the combined map's Gaussian blur, a share of the image's larger side; 0: none"},
      {"combination", EnumField<&O::combination, kCombinations>(),
       "sum: the weighted mean (the thesis); product: the weighted geometric mean"}};
  return fields;
}

std::string SaliencyOptions::Check() const {
  const std::string error = CheckFieldRanges(*this, Fields());
  if (!error.empty()) return error;
  if (local_maxima_window % 2 == 0) return "local_maxima_window must be odd";
  return "";
}

void NormaliseMap(const cv::Mat& map, const SaliencyOptions& options, cv::Mat* out) {
  CV_Assert(map.type() == CV_32FC1);
  double low = 0.0, high = 0.0;
  cv::minMaxLoc(map, &low, &high);
  if (!(high > low)) {
    out->create(map.size(), CV_32FC1);
    out->setTo(0.f);
    return;
  }
  map.convertTo(*out, CV_32FC1, 1.0 / (high - low), -low / (high - low));
  if (options.normalisation == "local_maxima") {
    *out *= LocalMaximaFactor(*out, options.local_maxima_window);
  }
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
                  cv::Size size, cv::Mat* out) {
  ATTEND_CHECK(normalised.size() == weights.size()) << "one weight per map";
  constexpr double kFloor = 0.01;  // so that a 0 somewhere is a strong veto, not -infinity
  out->create(size, CV_32FC1);
  out->setTo(0.f);
  double total = 0.0;
  for (const double weight : weights) total += weight;
  if (!(total > 0.0)) return;
  cv::Mat logs;
  for (size_t i = 0; i < normalised.size(); ++i) {
    if (weights[i] == 0.0) continue;
    cv::log(normalised[i] + kFloor, logs);
    cv::scaleAdd(logs, static_cast<float>(weights[i] / total), *out, *out);
  }
  cv::exp(*out, *out);
  // From [kFloor, 1 + kFloor] to [0, 1].
  *out = (*out - kFloor) / 1.0;
  cv::max(*out, 0.0, *out);
  cv::min(*out, 1.0, *out);
}

void SmoothSaliency(const SaliencyOptions& options, cv::Mat* map) {
  if (options.blur <= 0.0 || map->empty()) return;
  double low = 0.0, high = 0.0;
  cv::minMaxLoc(*map, &low, &high);
  const double sigma = options.blur * std::max(map->cols, map->rows);
  cv::GaussianBlur(*map, *map, cv::Size(), sigma, sigma, cv::BORDER_REPLICATE);
  double blurred_high = 0.0;
  cv::minMaxLoc(*map, nullptr, &blurred_high);
  if (blurred_high > 0.0) *map *= high / blurred_high;
}

}  // namespace attend
