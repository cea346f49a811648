#include "eval/weight_fit.h"

#include <cmath>
#include <functional>

#include "eval/fixation_metrics.h"
#include "util/error.h"

namespace attend {

namespace {

// The combined map of `sample` under `weights`, by the saliency stage's own functions.
void Combine(const FitSample& sample, const std::vector<double>& weights,
             const WeightFitOptions& options, cv::Mat* out) {
  const SaliencyOptions& saliency = options.saliency;
  const cv::Size size = sample.features[0].size();
  if (saliency.combination == SaliencyCombination::kProduct) {
    MultiplyMaps(sample.features, weights, options.additive, size, out);
  } else {
    CombineMaps(sample.features, weights, size, out);
  }
  SmoothSaliency(saliency, out);
}

// Every vector of `n` multiples of 1 / `units` summing to 1.
void ForEachOnSimplex(int n, int units, const std::function<void(const std::vector<double>&)>& f) {
  std::vector<int> counts(n, 0);
  std::function<void(int, int)> place = [&](int index, int left) {
    if (index == n - 1) {
      counts[index] = left;
      std::vector<double> weights(n);
      for (int i = 0; i < n; ++i) weights[i] = static_cast<double>(counts[i]) / units;
      f(weights);
      return;
    }
    for (int c = 0; c <= left; ++c) {
      counts[index] = c;
      place(index + 1, left - c);
    }
  };
  place(0, units);
}

}  // namespace

WeightFit FitWeights(const std::vector<FitSample>& samples, const WeightFitOptions& options) {
  ATTEND_CHECK(!samples.empty()) << "no training samples";
  const size_t n = samples[0].features.size();
  ATTEND_CHECK(n >= 1 && n <= 8) << "between 1 and 8 features";
  ATTEND_CHECK(options.step > 0.0 && options.step <= 1.0) << "step in (0, 1]";
  for (const FitSample& sample : samples) {
    ATTEND_CHECK(sample.features.size() == n) << "every sample has the same features";
  }
  const int units = std::max(1, static_cast<int>(std::lround(1.0 / options.step)));
  WeightFit best;
  best.nss = -std::numeric_limits<double>::infinity();
  cv::Mat combined;
  ForEachOnSimplex(static_cast<int>(n), units, [&](const std::vector<double>& weights) {
    ++best.candidates;
    double sum = 0.0;
    int counted = 0;
    for (const FitSample& sample : samples) {
      if (sample.fixations.empty()) continue;
      Combine(sample, weights, options, &combined);
      sum += Nss(combined, sample.fixations);
      ++counted;
    }
    const double mean = counted > 0 ? sum / counted : 0.0;
    if (mean > best.nss) {
      best.nss = mean;
      best.weights = weights;
    }
  });
  return best;
}

}  // namespace attend
