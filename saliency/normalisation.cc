#include "saliency/normalisation.h"

#include <opencv2/imgproc.hpp>
#include <utility>

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

// (F - min) / (max - min) over the frame into `out`; false (and `out` zeros) for a constant map.
bool ToUnitRange(const cv::Mat& map, cv::Mat* out) {
  CV_Assert(map.type() == CV_32FC1);
  double low = 0.0, high = 0.0;
  cv::minMaxLoc(map, &low, &high);
  if (!(high > low)) {
    out->create(map.size(), CV_32FC1);
    out->setTo(0.f);
    return false;
  }
  map.convertTo(*out, CV_32FC1, 1.0 / (high - low), -low / (high - low));
  return true;
}

// minmax (SPEC 2.3): the map onto [0, 1]; a constant map becomes 0.
void MinMaxNormalise(const cv::Mat& map, const SaliencyOptions&, cv::Mat* out) {
  ToUnitRange(map, out);
}

// local_maxima: Itti, Koch and Niebur's N(.) (saliency/saliency.h): the min-max map times
// (1 - m)^2.
void LocalMaximaNormalise(const cv::Mat& map, const SaliencyOptions& options, cv::Mat* out) {
  if (ToUnitRange(map, out)) *out *= LocalMaximaFactor(*out, options.local_maxima_window);
}

}  // namespace

const std::vector<BuiltinNormalisation>& BuiltinNormalisations() {
  static const std::vector<BuiltinNormalisation> table = {
      {"minmax", "(F - min) / (max - min) over the frame (SPEC 2.3)", &MinMaxNormalise},
      {"local_maxima", "Itti, Koch and Niebur's N(.): min-max times (1 - mean local maximum)^2",
       &LocalMaximaNormalise}};
  return table;
}

NormalisationRegistry::NormalisationRegistry() {
  for (const BuiltinNormalisation& row : BuiltinNormalisations()) {
    Entry entry;
    entry.name = row.name;
    entry.summary = row.summary;
    entry.origin = "built-in";
    entry.built_in = true;
    entry.normalise = row.normalise;
    entries_.emplace(row.name, std::move(entry));
  }
}

void NormalisationRegistry::Add(const std::string& name, const std::string& summary,
                                const std::string& origin, MapNormalisation normalise) {
  if (name.empty()) throw ConfigError(origin + ": registers a normalisation with an empty name");
  const auto found = entries_.find(name);
  if (found != entries_.end()) {
    throw ConfigError(origin + ": registers normalisation '" + name + "', which " +
                      (found->second.built_in ? std::string("is built in")
                                              : found->second.origin + " already registered"));
  }
  Entry entry;
  entry.name = name;
  entry.summary = summary;
  entry.origin = origin;
  entry.normalise = [normalise = std::move(normalise)](const cv::Mat& map, const SaliencyOptions&,
                                                       cv::Mat* out) { normalise(map, out); };
  entries_.emplace(name, std::move(entry));
}

const NormalisationRegistry::Entry* NormalisationRegistry::Find(const std::string& name) const {
  const auto found = entries_.find(name);
  return found == entries_.end() ? nullptr : &found->second;
}

std::vector<std::string> NormalisationRegistry::Names() const {
  std::vector<std::string> names = SaliencyOptions::Normalisations();
  for (const auto& [name, entry] : entries_) {
    if (!entry.built_in) names.push_back(name);
  }
  return names;
}

}  // namespace attend
