// Feature weights fitted to eye fixations (`attend fit-weights`, docs/FIXATIONS.md):
// the weights on a grid over the simplex (each a multiple of `step`, summing to 1) whose
// combined map has the highest mean NSS over the training images. NSS does not change when
// every weight is scaled, so the simplex holds every distinct combination.
#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "eval/fixation_data.h"
#include "saliency/saliency.h"

namespace attend {

struct FitSample {
  std::vector<cv::Mat> features;    // each feature's normalised map, CV_32FC1, one size
  std::vector<Fixation> fixations;  // in those maps' pixels
};

struct WeightFitOptions {
  SaliencyOptions saliency;  // how the maps combine and blur (its combination and blur)
  double step = 0.1;         // grid step of the weights, in (0, 1]
  // Per feature: added to the product's geometric mean (FeatureSpec::additive); empty: none.
  std::vector<bool> additive;
};

struct WeightFit {
  std::vector<double> weights;  // sum 1
  double nss = 0.0;             // mean over the samples
  int candidates = 0;           // weight vectors tried
};

// Throws std::invalid_argument-like errors (ATTEND_CHECK) for no samples, samples of
// different feature counts, or more than 8 features.
WeightFit FitWeights(const std::vector<FitSample>& samples, const WeightFitOptions& options);

}  // namespace attend
