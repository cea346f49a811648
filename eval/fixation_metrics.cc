#include "eval/fixation_metrics.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <opencv2/imgproc.hpp>
#include <random>

#include "util/error.h"
#include "util/strings.h"

namespace attend {

namespace {

// MATLAB's eps, which the MIT benchmark code adds to avoid log(0) and division by zero.
constexpr double kEps = 2.2204e-16;

std::string SizeText(cv::Size size) {
  return std::to_string(size.width) + "x" + std::to_string(size.height);
}

// The map as a continuous CV_64F matrix (shared, not copied, when it already is one).
cv::Mat AsDouble(const cv::Mat& map, const std::string& metric) {
  if (map.empty()) throw InputError(metric + ": the map is empty");
  if (map.channels() != 1 || (map.depth() != CV_32F && map.depth() != CV_64F)) {
    throw InputError(metric + ": the map must be one-channel CV_32F or CV_64F");
  }
  cv::Mat converted;
  if (map.depth() == CV_64F && map.isContinuous()) {
    converted = map;
  } else {
    map.convertTo(converted, CV_64F);
  }
  // A NaN would silently corrupt every sort and sum below.
  if (!cv::checkRange(converted)) throw InputError(metric + ": the map has non-finite values");
  return converted;
}

void CheckSameSize(const cv::Mat& a, const cv::Mat& b, const std::string& metric) {
  if (a.size() != b.size()) {
    throw InputError(metric + ": the maps differ in size (" + SizeText(a.size()) + " and " +
                     SizeText(b.size()) + ")");
  }
}

// The row-major index of the pixel a fixation is at, or -1 when it is outside the map.
int PixelIndex(cv::Size size, const Fixation& fixation) {
  if (!std::isfinite(fixation.x) || !std::isfinite(fixation.y)) return -1;
  // std::round takes halves away from zero, as MATLAB does.
  const double col = std::round(fixation.x), row = std::round(fixation.y);
  if (col < 0 || row < 0 || col >= size.width || row >= size.height) return -1;
  return static_cast<int>(row) * size.width + static_cast<int>(col);
}

// The fixated pixels (each once: the benchmark's binary fixation map), sorted.
std::vector<int> FixatedPixels(cv::Size size, const std::vector<Fixation>& fixations,
                               const std::string& metric) {
  std::vector<int> pixels;
  pixels.reserve(fixations.size());
  for (const Fixation& fixation : fixations) {
    const int index = PixelIndex(size, fixation);
    if (index >= 0) pixels.push_back(index);
  }
  std::sort(pixels.begin(), pixels.end());
  pixels.erase(std::unique(pixels.begin(), pixels.end()), pixels.end());
  if (pixels.empty()) {
    throw InputError(metric + ": no fixation falls inside the " + SizeText(size) + " map");
  }
  return pixels;
}

std::vector<double> ValuesAt(const cv::Mat& map, const std::vector<int>& pixels) {
  const double* values = map.ptr<double>(0);
  std::vector<double> out;
  out.reserve(pixels.size());
  for (int index : pixels) out.push_back(values[index]);
  return out;
}

// Trapezoidal area under a curve given by its vertices in order of increasing fp.
double Trapezoid(const std::vector<double>& fp, const std::vector<double>& tp) {
  double area = 0.0;
  for (size_t i = 1; i < fp.size(); ++i) area += (fp[i] - fp[i - 1]) * (tp[i] + tp[i - 1]) / 2;
  return area;
}

// (v - min) / (max - min) maps the map to [0, 1]; a constant map goes to 0.
struct RangeNormaliser {
  explicit RangeNormaliser(const cv::Mat& map) {
    cv::minMaxLoc(map, &min, &max);
    // A range at the level of float rounding (a constant map resized for scoring) is no range:
    // stretching it to [0, 1] would make noise of the last bits into structure.
    if (max - min <= 1e-6 * std::max(std::abs(min), std::abs(max))) max = min;
  }
  bool constant() const { return !(max > min); }
  double operator()(double v) const { return max > min ? (v - min) / (max - min) : 0.0; }
  double min = 0.0, max = 0.0;
};

// The number of values of the ascending `sorted` that are >= t.
int CountAtLeast(const std::vector<double>& sorted, double t) {
  return static_cast<int>(sorted.end() - std::lower_bound(sorted.begin(), sorted.end(), t));
}

// The AUC of positives against negatives (both range-normalised) with the thresholds 0, step,
// 2 step, ... up to the largest value, as the MIT code's AUC_Borji and AUC_shuffled.
double AucAtSteps(std::vector<double> positives, std::vector<double> negatives, double step) {
  std::sort(positives.begin(), positives.end());
  std::sort(negatives.begin(), negatives.end());
  const double top = std::max(positives.back(), negatives.back());
  // The tolerance keeps a threshold that equals the top but for rounding (e.g. 10 x 0.1).
  const int count = static_cast<int>(std::floor(top / step + 1e-9)) + 1;
  std::vector<double> tp = {0.0}, fp = {0.0};
  for (int i = count - 1; i >= 0; --i) {
    const double threshold = i * step;
    tp.push_back(static_cast<double>(CountAtLeast(positives, threshold)) / positives.size());
    fp.push_back(static_cast<double>(CountAtLeast(negatives, threshold)) / negatives.size());
  }
  tp.push_back(1.0);
  fp.push_back(1.0);
  return Trapezoid(fp, tp);
}

// A uniform integer in [0, n): the multiply-shift keeps results the same on every standard
// library (std::uniform_int_distribution's algorithm is unspecified).
size_t UniformIndex(std::mt19937_64& rng, size_t n) {
  return static_cast<size_t>((static_cast<unsigned __int128>(rng()) * n) >> 64);
}

// The map as a distribution for KL: shifted to a minimum of 0 when it has negative values,
// divided by its sum (uniform when the sum is 0).
cv::Mat KlDistribution(const cv::Mat& map) {
  double min = 0.0;
  cv::minMaxLoc(map, &min, nullptr);
  cv::Mat shifted = min < 0.0 ? cv::Mat(map - min) : map;
  const double sum = cv::sum(shifted)[0];
  if (sum <= 0.0) return cv::Mat(map.size(), CV_64F, cv::Scalar(1.0 / map.total()));
  return shifted / sum;
}

// Range-normalised to [0, 1], plus `offset`, divided by the sum; uniform when that sum is 0
// (a constant map with no offset).
cv::Mat RangeDistribution(const cv::Mat& map, double offset) {
  const RangeNormaliser normalise(map);
  cv::Mat out = !normalise.constant()
                    ? cv::Mat((map - normalise.min) / (normalise.max - normalise.min))
                    : cv::Mat(map.size(), CV_64F, cv::Scalar(0.0));
  out += offset;
  const double sum = cv::sum(out)[0];
  if (sum <= 0.0) return cv::Mat(map.size(), CV_64F, cv::Scalar(1.0 / map.total()));
  return out / sum;
}

// The sampled Gaussian of cv::getGaussianKernel for a float image's automatic size: taps to
// 4 sigma either side, summing to 1.
std::vector<double> GaussianKernel(double sigma) {
  const int size = cvRound(sigma * 4 * 2 + 1) | 1;
  const cv::Mat kernel = cv::getGaussianKernel(size, sigma, CV_64F);
  return std::vector<double>(kernel.begin<double>(), kernel.end<double>());
}

struct MetricField {
  const char* name;
  double FixationScores::*field;
};

// The one list of metrics: names and fields cannot drift apart.
constexpr std::array<MetricField, 8> kMetricFields = {{
    {"nss", &FixationScores::nss},
    {"auc_judd", &FixationScores::auc_judd},
    {"auc_borji", &FixationScores::auc_borji},
    {"sauc", &FixationScores::sauc},
    {"cc", &FixationScores::cc},
    {"kl", &FixationScores::kl},
    {"sim", &FixationScores::sim},
    {"ig", &FixationScores::ig},
}};

}  // namespace

cv::Mat FixationDensity(cv::Size size, const std::vector<Fixation>& fixations, double sigma) {
  ATTEND_CHECK(sigma > 0.0) << "sigma " << sigma;
  ATTEND_CHECK(size.width > 0 && size.height > 0) << "size " << SizeText(size);
  // The fixation count of each pixel, by row: a pixel fixated twice weighs twice.
  std::map<int, std::vector<int>> columns_by_row;
  for (const Fixation& fixation : fixations) {
    const int index = PixelIndex(size, fixation);
    if (index >= 0) columns_by_row[index / size.width].push_back(index % size.width);
  }
  if (columns_by_row.empty()) {
    throw InputError("fixation density: no fixation falls inside the " + SizeText(size) + " image");
  }
  // cv::GaussianBlur of the count map with zero beyond the image (nobody fixated there, so
  // reflecting would invent fixations), done as separable splats: a general blur with a
  // 1-degree kernel (~780 taps at 3888 px) takes ~20 s, the splats cost rows x taps x width.
  const std::vector<double> kernel = GaussianKernel(sigma);
  const int half = static_cast<int>(kernel.size() / 2);
  cv::Mat density(size, CV_64F, cv::Scalar(0.0));
  std::vector<double> row_profile(size.width);
  for (const auto& [row, columns] : columns_by_row) {
    std::fill(row_profile.begin(), row_profile.end(), 0.0);
    for (int column : columns) {  // the horizontal pass of this row
      const int first = std::max(0, column - half), last = std::min(size.width - 1, column + half);
      for (int c = first; c <= last; ++c) row_profile[c] += kernel[c - column + half];
    }
    const int first = std::max(0, row - half), last = std::min(size.height - 1, row + half);
    for (int r = first; r <= last; ++r) {  // the vertical pass: this row's share of row r
      const double weight = kernel[r - row + half];
      double* out = density.ptr<double>(r);
      for (int c = 0; c < size.width; ++c) out[c] += weight * row_profile[c];
    }
  }
  return density / cv::sum(density)[0];
}

double Nss(const cv::Mat& map, const std::vector<Fixation>& fixations) {
  const cv::Mat values = AsDouble(map, "NSS");
  const std::vector<int> pixels = FixatedPixels(values.size(), fixations, "NSS");
  cv::Scalar mean, sd;
  cv::meanStdDev(values, mean, sd);
  if (sd[0] <= 0.0) return 0.0;  // a constant map says nothing about where people look
  double total = 0.0;
  for (double v : ValuesAt(values, pixels)) total += (v - mean[0]) / sd[0];
  return total / pixels.size();
}

double AucJudd(const cv::Mat& map, const std::vector<Fixation>& fixations) {
  const cv::Mat values = AsDouble(map, "AUC-Judd");
  const std::vector<int> pixels = FixatedPixels(values.size(), fixations, "AUC-Judd");
  const size_t total = values.total();
  if (pixels.size() == total) throw InputError("AUC-Judd: every pixel is fixated (no negatives)");

  // The distinct values at fixations, ascending, are the thresholds.
  std::vector<double> thresholds = ValuesAt(values, pixels);
  std::sort(thresholds.begin(), thresholds.end());
  const std::vector<double> fixated = thresholds;
  thresholds.erase(std::unique(thresholds.begin(), thresholds.end()), thresholds.end());

  // above[k] = pixels >= thresholds[k - 1], by one pass that bins each pixel under the largest
  // threshold it reaches (O(N log K) instead of sorting all N pixels).
  std::vector<size_t> above(thresholds.size() + 1, 0);
  const double* data = values.ptr<double>(0);
  for (size_t i = 0; i < total; ++i) {
    ++above[std::upper_bound(thresholds.begin(), thresholds.end(), data[i]) - thresholds.begin()];
  }
  for (size_t k = above.size() - 1; k > 0; --k) above[k - 1] += above[k];

  const double positives = static_cast<double>(pixels.size());
  const double negatives = static_cast<double>(total - pixels.size());
  std::vector<double> tp = {0.0}, fp = {0.0};
  for (size_t j = thresholds.size(); j-- > 0;) {  // from the highest threshold down
    const size_t hits = CountAtLeast(fixated, thresholds[j]);
    tp.push_back(hits / positives);
    fp.push_back((above[j + 1] - hits) / negatives);
  }
  tp.push_back(1.0);
  fp.push_back(1.0);
  return Trapezoid(fp, tp);
}

double AucBorji(const cv::Mat& map, const std::vector<Fixation>& fixations, int splits, double step,
                uint64_t seed) {
  ATTEND_CHECK(splits > 0) << "splits " << splits;
  ATTEND_CHECK(step > 0.0 && step <= 1.0) << "step " << step;
  const cv::Mat values = AsDouble(map, "AUC-Borji");
  const std::vector<int> pixels = FixatedPixels(values.size(), fixations, "AUC-Borji");
  const RangeNormaliser normalise(values);
  std::vector<double> positives = ValuesAt(values, pixels);
  for (double& v : positives) v = normalise(v);

  const double* data = values.ptr<double>(0);
  std::mt19937_64 rng(seed);
  double total = 0.0;
  std::vector<double> negatives(pixels.size());
  for (int split = 0; split < splits; ++split) {
    for (double& v : negatives) v = normalise(data[UniformIndex(rng, values.total())]);
    total += AucAtSteps(positives, negatives, step);
  }
  return total / splits;
}

double ShuffledAuc(const cv::Mat& map, const std::vector<Fixation>& fixations,
                   const std::vector<Fixation>& other_fixations, int splits, double step,
                   uint64_t seed) {
  ATTEND_CHECK(splits > 0) << "splits " << splits;
  ATTEND_CHECK(step > 0.0 && step <= 1.0) << "step " << step;
  const cv::Mat values = AsDouble(map, "shuffled AUC");
  const std::vector<int> pixels = FixatedPixels(values.size(), fixations, "shuffled AUC");
  std::vector<int> others =
      FixatedPixels(values.size(), other_fixations, "shuffled AUC (other images' fixations)");
  const RangeNormaliser normalise(values);
  std::vector<double> positives = ValuesAt(values, pixels);
  for (double& v : positives) v = normalise(v);

  const double* data = values.ptr<double>(0);
  const size_t drawn = std::min(pixels.size(), others.size());
  std::mt19937_64 rng(seed);
  double total = 0.0;
  std::vector<double> negatives(drawn);
  for (int split = 0; split < splits; ++split) {
    // A partial Fisher-Yates shuffle: the first `drawn` entries become a uniform sample
    // without replacement, whatever order the previous split left.
    for (size_t i = 0; i < drawn; ++i) {
      std::swap(others[i], others[i + UniformIndex(rng, others.size() - i)]);
      negatives[i] = normalise(data[others[i]]);
    }
    total += AucAtSteps(positives, negatives, step);
  }
  return total / splits;
}

double Cc(const cv::Mat& map, const cv::Mat& density) {
  const cv::Mat a = AsDouble(map, "CC");
  const cv::Mat b = AsDouble(density, "CC");
  CheckSameSize(a, b, "CC");
  const double mean_a = cv::mean(a)[0], mean_b = cv::mean(b)[0];
  const double* pa = a.ptr<double>(0);
  const double* pb = b.ptr<double>(0);
  double ab = 0.0, aa = 0.0, bb = 0.0;
  for (size_t i = 0; i < a.total(); ++i) {
    const double da = pa[i] - mean_a, db = pb[i] - mean_b;
    ab += da * db;
    aa += da * da;
    bb += db * db;
  }
  if (aa <= 0.0 || bb <= 0.0) return 0.0;  // undefined for a constant map; no linear relation
  return ab / std::sqrt(aa * bb);
}

double Kl(const cv::Mat& map, const cv::Mat& density) {
  const cv::Mat a = AsDouble(map, "KL");
  const cv::Mat b = AsDouble(density, "KL");
  CheckSameSize(a, b, "KL");
  const cv::Mat p = KlDistribution(a), q = KlDistribution(b);
  const double* pp = p.ptr<double>(0);
  const double* pq = q.ptr<double>(0);
  double kl = 0.0;
  for (size_t i = 0; i < p.total(); ++i) kl += pq[i] * std::log(kEps + pq[i] / (pp[i] + kEps));
  return kl;
}

double Sim(const cv::Mat& map, const cv::Mat& density) {
  const cv::Mat a = AsDouble(map, "SIM");
  const cv::Mat b = AsDouble(density, "SIM");
  CheckSameSize(a, b, "SIM");
  cv::Mat intersection;
  cv::min(RangeDistribution(a, 0.0), RangeDistribution(b, 0.0), intersection);
  return cv::sum(intersection)[0];
}

double InformationGain(const cv::Mat& map, const cv::Mat& baseline,
                       const std::vector<Fixation>& fixations) {
  const cv::Mat a = AsDouble(map, "IG");
  const cv::Mat b = AsDouble(baseline, "IG");
  CheckSameSize(a, b, "IG");
  const std::vector<int> pixels = FixatedPixels(a.size(), fixations, "IG");
  const std::vector<double> p = ValuesAt(RangeDistribution(a, kEps), pixels);
  const std::vector<double> q = ValuesAt(RangeDistribution(b, kEps), pixels);
  double total = 0.0;
  for (size_t i = 0; i < pixels.size(); ++i) {
    total += std::log2(p[i] + kEps) - std::log2(q[i] + kEps);
  }
  return total / pixels.size();
}

cv::Mat CentreBias(cv::Size size, double sigma_fraction) {
  ATTEND_CHECK(sigma_fraction > 0.0) << "sigma_fraction " << sigma_fraction;
  ATTEND_CHECK(size.width > 0 && size.height > 0) << "size " << SizeText(size);
  // Separable: the 2-D Gaussian is the outer product of a column and a row profile.
  const auto profile = [](int n, double sigma) {
    cv::Mat p(1, n, CV_64F);
    const double centre = (n - 1) / 2.0;
    for (int i = 0; i < n; ++i) {
      const double d = (i - centre) / sigma;
      p.at<double>(0, i) = std::exp(-0.5 * d * d);
    }
    return p;
  };
  const cv::Mat rows = profile(size.height, sigma_fraction * size.height);
  const cv::Mat cols = profile(size.width, sigma_fraction * size.width);
  cv::Mat bias = rows.t() * cols;
  double max = 0.0;
  cv::minMaxLoc(bias, nullptr, &max);
  return bias / max;
}

MeanInterval MeanWithInterval(const std::vector<double>& values) {
  ATTEND_CHECK(!values.empty()) << "no values";
  MeanInterval out;
  out.n = static_cast<int>(values.size());
  double sum = 0.0;
  for (double v : values) sum += v;
  out.mean = sum / out.n;
  out.low = out.high = out.mean;
  if (out.n < 2) return out;
  double squares = 0.0;
  for (double v : values) squares += (v - out.mean) * (v - out.mean);
  const double sd = std::sqrt(squares / (out.n - 1));
  const double half = 1.96 * sd / std::sqrt(static_cast<double>(out.n));
  out.low = out.mean - half;
  out.high = out.mean + half;
  return out;
}

FixationScores ScoreMap(const cv::Mat& map, const std::vector<Fixation>& fixations,
                        const std::vector<Fixation>& other_fixations, const cv::Mat& density,
                        const cv::Mat& baseline) {
  // Converted once here rather than once per metric.
  const cv::Mat values = AsDouble(map, "saliency map");
  const cv::Mat density_values = AsDouble(density, "fixation density");
  const cv::Mat baseline_values = AsDouble(baseline, "baseline map");
  CheckSameSize(values, density_values, "saliency map and fixation density");
  CheckSameSize(values, baseline_values, "saliency map and baseline map");
  FixationScores scores;
  scores.nss = Nss(values, fixations);
  scores.auc_judd = AucJudd(values, fixations);
  scores.auc_borji = AucBorji(values, fixations);
  scores.sauc = ShuffledAuc(values, fixations, other_fixations);
  scores.cc = Cc(values, density_values);
  scores.kl = Kl(values, density_values);
  scores.sim = Sim(values, density_values);
  scores.ig = InformationGain(values, baseline_values, fixations);
  return scores;
}

const std::vector<std::string>& FixationMetricNames() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> out;
    for (const MetricField& metric : kMetricFields) out.push_back(metric.name);
    return out;
  }();
  return names;
}

double Get(const FixationScores& scores, const std::string& name) {
  for (const MetricField& metric : kMetricFields) {
    if (name == metric.name) return scores.*metric.field;
  }
  throw ConfigError("unknown fixation metric '" + name + "'" +
                    DidYouMean(name, FixationMetricNames()) +
                    " (known: " + Join(FixationMetricNames(), ", ") + ")");
}

}  // namespace attend
