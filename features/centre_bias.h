// The `centre_bias` plugin: people looking at a photograph look near its centre (Tatler 2007;
// the centre prior of the MIT saliency benchmark). Not in the thesis, whose scenes are a robot's
// view rather than framed photographs. The map is a Gaussian centred on the image,
//
//   C(x, y) = exp(-((x - cx)^2 / (2 (s w)^2) + (y - cy)^2 / (2 (s h)^2)))
//
// with s = `sigma` (a share of the width w and height h) and (cx, cy) the image centre: an
// anisotropic Gaussian that follows the image's aspect ratio. It does not depend on the frame's
// content, only on its size.
#pragma once

#include <memory>
#include <opencv2/core.hpp>

#include "features/feature_map.h"
#include "util/option_fields.h"

namespace attend {

struct CentreBiasOptions {
  double sigma = 0.25;  // share of the width and height
  static const OptionFields<CentreBiasOptions>& Fields();
};

// Fills `out` (CV_32FC1 of `size`) with the centre-bias Gaussian of relative sigma `sigma`.
void CentreBiasMap(cv::Size size, double sigma, cv::Mat* out);

// Parameters: CentreBiasOptions::Fields().
std::unique_ptr<FeatureMap> CreateCentreBiasFeature(const ParamBlock& params,
                                                    const FeatureSetup& setup);

}  // namespace attend
