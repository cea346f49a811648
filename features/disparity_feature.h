// The `disparity` plugin (thesis 5.1.1, SPEC 2.3): relative depth from the stereo pair, nearer
// being more salient. The map is the disparity (stereo/disparity.h) divided by D - 1, so in
// [0, 1]; with `per_region` each BIP colour region gets the mean over its pixels, which steadies
// the map on untextured surfaces and at depth edges. It needs a stereo source.
#pragma once

#include <memory>

#include "features/feature_map.h"

namespace attend {

// Parameters: max_disparity (D), window, subpixel, left_right_check, lr_tolerance, per_region.
std::unique_ptr<FeatureMap> CreateDisparityFeature(const ParamBlock& params,
                                                   const FeatureSetup& setup);

}  // namespace attend
