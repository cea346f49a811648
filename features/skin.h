// The `skin` plugin (thesis 5.1.1, SPEC 2.3): every pixel's TSL chrominance is compared with
// the skin model (features/skin_model.h). The binary map of the thesis is 1 where the squared
// Mahalanobis distance is below T_s and 0 elsewhere; the soft map is
// max(0, 1 - sqrt(d^2 / T_s)), the Mahalanobis distance as a fraction of the threshold's,
// which is also 0 outside the skin ellipse and rises to 1 at the model's mean. With
// `per_region`, each BIP colour region gets the mean of its pixels' values, which removes the
// isolated pixels that camera noise pushes across the threshold on near-grey surfaces.
#pragma once

#include <memory>
#include <opencv2/core.hpp>

#include "features/feature_map.h"
#include "features/skin_model.h"

namespace attend {

enum class SkinOutput { kBinary, kSoft };

// The skin map of a TSL image (CV_32FC3, colour/colour.h) as CV_32FC1.
void SkinMap(const cv::Mat& tsl, const SkinModel& model, SkinOutput output, cv::Mat* out);

// Each region's mean of `map` painted over its pixels (0 outside the mask).
void AverageOverRegions(const Segmentation& segmentation, cv::Mat* map);

// Parameters: `model` (a model file, default configs/skin_tsl.yaml), `output` (binary | soft),
// `per_region` (bool, default false).
std::unique_ptr<FeatureMap> CreateSkinFeature(const ParamBlock& params, const FeatureSetup& setup);

}  // namespace attend
