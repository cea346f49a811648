// The `disparity` plugin (thesis 5.1.1, SPEC 2.3): relative depth from the stereo pair. Two
// scores:
//   contrast (the default)  how much nearer a pixel is than its surround and than the ground
//                           (stereo/depth_contrast.h), 0 where no disparity was measured, then
//                           each BIP colour region's mean over its measured pixels (a plain
//                           object is measured at its edges only): an object stands out
//                           against what is behind it, the road and the sky do not;
//   nearness (the thesis)   nearer is more salient: the disparity (stereo/disparity.h) divided
//                           by D - 1, so in [0, 1]; on a street the road in front of the camera
//                           ranks first.
// With `per_region` each BIP colour region gets the mean over its pixels, which steadies the map
// on untextured surfaces and at depth edges. It needs a stereo source.
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
  std::string score = "contrast";  // contrast or nearness (the thesis's)
  float surround = 0.15f;          // contrast: the surround window's side, a share of the width
  // The feature's own keys.
  static const OptionFields<DisparityFeatureOptions>& Fields();
};

// Parameters: DisparityOptions::Fields() and DisparityFeatureOptions::Fields().
std::unique_ptr<FeatureMap> CreateDisparityFeature(const ParamBlock& params,
                                                   const FeatureSetup& setup);

}  // namespace attend
