#include "eval/weight_fit.h"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "eval/fixation_metrics.h"

namespace attend {
namespace {

// Samples with two features: the first peaks where people looked (a blurred fixation map),
// the second is noise. The fitted weights must put everything on the first.
std::vector<FitSample> Samples() {
  std::vector<FitSample> samples;
  cv::RNG rng(5);
  for (int i = 0; i < 6; ++i) {
    FitSample sample;
    for (int k = 0; k < 8; ++k) {
      sample.fixations.push_back({k % 3, rng.uniform(5.0, 55.0), rng.uniform(5.0, 35.0)});
    }
    cv::Mat informative = FixationDensity({60, 40}, sample.fixations, 3.0);
    informative.convertTo(informative, CV_32F);
    cv::normalize(informative, informative, 0, 1, cv::NORM_MINMAX);
    cv::Mat noise(40, 60, CV_32FC1);
    rng.fill(noise, cv::RNG::UNIFORM, 0.f, 1.f);
    sample.features = {noise, informative};
    samples.push_back(sample);
  }
  return samples;
}

TEST(FitWeights, PutsTheWeightOnTheFeatureThatPredictsTheFixations) {
  for (const bool product : {false, true}) {
    WeightFitOptions options;
    options.saliency.combination =
        product ? SaliencyCombination::kProduct : SaliencyCombination::kSum;
    options.step = 0.25;
    const WeightFit fit = FitWeights(Samples(), options);
    ASSERT_EQ(fit.weights.size(), 2u);
    EXPECT_DOUBLE_EQ(fit.weights[0], 0.0) << "product " << product;
    EXPECT_DOUBLE_EQ(fit.weights[1], 1.0) << "product " << product;
    EXPECT_EQ(fit.candidates, 5);  // 0, 0.25, ..., 1 on the first weight
    EXPECT_GT(fit.nss, 2.0);
  }
}

TEST(FitWeights, TheFittedNssIsTheBestOnTheGrid) {
  // Every grid point scores at most the fitted NSS: check the two ends against it.
  const std::vector<FitSample> samples = Samples();
  WeightFitOptions options;
  options.step = 0.5;
  const WeightFit fit = FitWeights(samples, options);
  double noise_only = 0.0;
  for (const FitSample& sample : samples) noise_only += Nss(sample.features[0], sample.fixations);
  noise_only /= samples.size();
  EXPECT_GT(fit.nss, noise_only);
  EXPECT_EQ(fit.candidates, 3);
}

}  // namespace
}  // namespace attend
