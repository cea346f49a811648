#include "saliency/saliency_stage.h"

#include "util/shared_mat.h"

#include <cmath>
#include <utility>

#include "util/error.h"
#include "util/float_checks.h"

namespace attend {

namespace {

// A plugin's normalisation must give CV_32FC1 of the map's size with values in [0, 1]; anything
// else is a configuration error naming the feature and the library (a broken plugin was
// configured), as for a feature's own map.
void CheckNormalisedMap(const SaliencyInput& input, const cv::Mat& normalised, cv::Size size) {
  const std::string who =
      "the normalisation of feature '" + input.name + "' (" + input.normalisation.origin + ")";
  if (normalised.type() != CV_32FC1 || normalised.size() != size) {
    throw ConfigError(who + " returned a map that is not CV_32FC1 of the feature map's size");
  }
  if (!AllFloatsWithin(normalised, 0.f, 1.f)) {
    throw ConfigError(who + " returned values outside [0, 1] or not finite");
  }
}

}  // namespace

SaliencyStage::SaliencyStage(const SaliencyOptions& options,
                             const NormalisationRegistry::Entry& normalisation,
                             std::vector<SaliencyInput> inputs)
    : options_(options), inputs_(std::move(inputs)) {
  ATTEND_CHECK(normalisation.normalise) << "the saliency stage needs a normalisation";
  for (SaliencyInput& input : inputs_) {
    if (!input.normalisation.normalise) input.normalisation = normalisation;
  }
  normalised_.resize(inputs_.size());
}

void SaliencyStage::Combine(const std::vector<const cv::Mat*>& maps, bool grey, cv::Size size) {
  ATTEND_CHECK(maps.size() == inputs_.size()) << "one map per input";
  // Maps of the last frame that someone still holds are let go (util/shared_mat.h).
  for (cv::Mat& map : normalised_) ReleaseIfShared(&map);
  ReleaseIfShared(&saliency_);
  frame_weights_.resize(inputs_.size());
  additive_.resize(inputs_.size());
  for (size_t i = 0; i < inputs_.size(); ++i) {
    const SaliencyInput& input = inputs_[i];
    input.normalisation.normalise(*maps[i], options_, &normalised_[i]);
    if (!input.normalisation.built_in) CheckNormalisedMap(input, normalised_[i], maps[i]->size());
    // SPEC 2.3 divides by the sum of all weights. A grey frame has no colour, so there colour
    // features measure nothing rather than "no contrast"; counting their weights would cap
    // the saliency of grey input at the share of the other features, below
    // select.min_saliency for a plainly bright object. Colour frames keep the weights as
    // configured.
    frame_weights_[i] = input.weight;
    additive_[i] = input.additive;
    if (grey) {
      double low = 0.0, high = 0.0;
      cv::minMaxLoc(*maps[i], &low, &high);
      if (!(high > low)) frame_weights_[i] = 0.0;
    }
  }
  if (options_.combination == SaliencyCombination::kProduct) {
    MultiplyMaps(normalised_, frame_weights_, additive_, size, &saliency_);
  } else {
    CombineMaps(normalised_, frame_weights_, size, &saliency_);
  }
  SmoothSaliency(options_, &saliency_);
}

}  // namespace attend
