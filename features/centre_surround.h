// The `centre_surround` plugin: colour and intensity contrast at several scales, as
// centre-surround differences (Itti, Koch and Niebur, PAMI 1998; not in the thesis, whose
// contrast features are per BIP region at one segmentation). The image in CIE Lab
// (L, a, b each in [0, 1]) is blurred by Gaussians of sigma c (the centre) and r x c (the
// surround) for each c in `scales` (px at the working size); the scale's map is the Euclidean
// distance between centre and surround over the three channels, min-max normalised; the
// feature is the mean of the scales' maps. A small thing that differs from its surroundings in
// any of lightness, red-green or yellow-blue stands out at the scale that matches its size.
#pragma once

#include <memory>
#include <opencv2/core.hpp>
#include <vector>

#include "features/feature_map.h"
#include "util/option_fields.h"

namespace attend {

struct CentreSurroundOptions {
  std::vector<double> scales = {2.0, 4.0, 8.0};  // centre sigmas, px
  double surround = 4.0;                         // surround sigma / centre sigma
  // "" when valid; otherwise names the field and the broken constraint.
  std::string Check() const;
  // The range of each of `scales`, and of the numeric fields (util/option_fields.h); Check and
  // the feature's keys apply them.
  static Range ScaleRange() { return Range::AboveUpTo(0, 200); }
  static const OptionFields<CentreSurroundOptions>& Fields();
};

// `bgr`: 8-bit BGR. Fills `out` (CV_32FC1, [0, 1]).
void CentreSurroundMap(const cv::Mat& bgr, const CentreSurroundOptions& options, cv::Mat* out);

// Parameters: CentreSurroundOptions::Fields().
std::unique_ptr<FeatureMap> CreateCentreSurroundFeature(const ParamBlock& params,
                                                        const FeatureSetup& setup);

}  // namespace attend
