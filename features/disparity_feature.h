// The `disparity` plugin (thesis 5.1.1, SPEC 2.3): relative depth from the stereo pair, nearer
// being more salient. The map is the disparity (stereo/disparity.h) divided by D - 1, so in
// [0, 1]; with `per_region` each BIP colour region gets the mean over its pixels, which steadies
// the map on untextured surfaces and at depth edges. It needs a stereo source.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "features/feature_map.h"
#include "stereo/disparity.h"

namespace attend {

// The keys of DisparityOptions (DisparityOptions::Fields), as the `disparity` feature and
// `attend disparity --set disparity.KEY=VALUE` name them.
const std::vector<std::string>& DisparityOptionKeys();

// The one binding of DisparityOptions: its fields read from `block` over `options`, then
// DisparityOptions::Check. A wrong type, or a value Check
// refuses: ConfigError naming the key and where it was written. Other keys are left to the
// caller (CheckNoUnknownKeys).
DisparityOptions ReadDisparityOptions(const ParamBlock& block, DisparityOptions options = {});

// The `disparity` feature's parameters: the estimator's, and its own.
struct DisparityFeatureOptions {
  DisparityOptions disparity;  // its keys: DisparityOptions::Fields()
  bool per_region = false;     // each BIP colour region takes the mean disparity of its pixels
  // The feature's own keys.
  static const OptionFields<DisparityFeatureOptions>& Fields();
};

// Parameters: DisparityOptions::Fields() and DisparityFeatureOptions::Fields().
std::unique_ptr<FeatureMap> CreateDisparityFeature(const ParamBlock& params,
                                                   const FeatureSetup& setup);

}  // namespace attend
