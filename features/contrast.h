// Colour and intensity contrast of the BIP colour regions (thesis 5.1.1, eq. 5.1 and 5.2;
// SPEC 2.3). Both are mean gradients along a region's boundary:
//   MCG_i = (S_i / PL_i) sum_j pl_ij d(C_i, C_j)    MIG_i = (1 / PL_i) sum_j pl_ij |I_i - I_j|
// with S_i the mean saturation in [0, 1], C the mean HSV-cylinder colour, I the mean V in
// [0, 255], PL_i the region's 4-neighbour pixel edges to other regions (image border and
// pixels outside the mask excluded) and pl_ij those shared with region j. A region without
// neighbours scores 0.
#pragma once

#include <memory>
#include <opencv2/core.hpp>
#include <vector>

#include "features/feature_map.h"
#include "pyramid/segmentation.h"

namespace attend {

// Per-region values, indexed by region label.
std::vector<float> ColourContrast(const Segmentation& segmentation);
std::vector<float> IntensityContrast(const Segmentation& segmentation);

// Paints per-region values onto their pixels (CV_32FC1; 0 where the label is negative).
void PaintRegions(const cv::Mat& labels, const std::vector<float>& values, cv::Mat* out);

// The `colour_contrast` and `intensity_contrast` plugins (no parameters).
std::unique_ptr<FeatureMap> CreateColourContrast(const ParamBlock& params,
                                                 const FeatureSetup& setup);
std::unique_ptr<FeatureMap> CreateIntensityContrast(const ParamBlock& params,
                                                    const FeatureSetup& setup);

}  // namespace attend
