// The saliency stage (thesis 5.1.1.2, SPEC 2.3): each feature map normalised by its chosen
// normalisation, weighted, and combined (sum or product) into the saliency map, which is then
// smoothed as saliency.blur says. On a grey frame a feature whose map is constant (colour
// contrast and skin, which see nothing there) weighs 0, so it does not dilute the features
// that see something (docs/ATTENTION.md, "Real and grey input").
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "saliency/normalisation.h"
#include "saliency/saliency.h"

namespace attend {

// One feature map's place in the combination.
struct SaliencyInput {
  std::string name;  // the feature's, for messages
  double weight = 1.0;
  // Its normalisation (a copy of the registry's entry); without a `normalise`, that of
  // saliency.normalisation.
  NormalisationRegistry::Entry normalisation;
  bool additive = false;  // FeatureSpec::additive
};

class SaliencyStage {
 public:
  // `normalisation` is saliency.normalisation's entry in the registry.
  SaliencyStage(const SaliencyOptions& options, const NormalisationRegistry::Entry& normalisation,
                std::vector<SaliencyInput> inputs);

  // Combines `maps` (CV_32FC1, one per input, in order, each `size`). `grey`: the frame has no
  // colour. A plugin's normalisation that returns a map not CV_32FC1 of the map's size, or
  // values outside [0, 1]: ConfigError naming the feature and the library.
  void Combine(const std::vector<const cv::Mat*>& maps, bool grey, cv::Size size);

  // Each map normalised, in the inputs' order, and the combined map, of the last Combine.
  const std::vector<cv::Mat>& normalised() const { return normalised_; }
  const cv::Mat& saliency() const { return saliency_; }
  // The weights the last Combine used (a grey frame's constant maps at 0).
  const std::vector<double>& weights() const { return frame_weights_; }

 private:
  SaliencyOptions options_;
  std::vector<SaliencyInput> inputs_;
  std::vector<cv::Mat> normalised_;
  std::vector<double> frame_weights_;
  std::vector<bool> additive_;
  cv::Mat saliency_;
};

}  // namespace attend
