// The `skin` plugin (thesis 5.1.1, SPEC 2.3): every pixel's TSL chrominance is compared with
// the skin model (colour/skin_model.h). The binary map of the thesis is 1 where the squared
// Mahalanobis distance is below T_s and 0 elsewhere; the soft map is
// max(0, 1 - sqrt(d^2 / T_s)), the Mahalanobis distance as a fraction of the threshold's,
// which is also 0 outside the skin ellipse and rises to 1 at the model's mean. With
// `per_region`, each BIP colour region gets the mean of its pixels' values, which removes the
// isolated pixels that camera noise pushes across the threshold on near-grey surfaces.
#pragma once

#include <memory>
#include <opencv2/core.hpp>
#include <string>

#include "colour/skin_model.h"
#include "features/feature_map.h"
#include "util/option_fields.h"

namespace attend {

enum class SkinOutput { kBinary, kSoft };

// The `skin` feature's parameters.
struct SkinFeatureOptions {
  SkinOutput output = SkinOutput::kBinary;
  std::string model = "configs/skin_tsl.yaml";  // resolved by FeatureSetup::ResolvePath
  bool per_region = false;  // each BIP colour region takes the mean of its pixels' values
  static const OptionFields<SkinFeatureOptions>& Fields();
};

// The skin map of a TSL image (CV_32FC3, colour/colour.h) as CV_32FC1.
void SkinMap(const cv::Mat& tsl, const SkinModel& model, SkinOutput output, cv::Mat* out);
// The same map from the image's SkinDistanceMap for `model` (`distance`, which `out` may be).
void SkinMapFromDistance(const cv::Mat& distance, const SkinModel& model, SkinOutput output,
                         cv::Mat* out);

// The squared Mahalanobis distance d^2 of every pixel's chrominance to the model's mean
// (CV_32FC1), the quantity SkinMap thresholds: d^2 < T_s is skin, d^2 < confident x T_s is
// confident skin (SkinRegionOptions).
void SkinDistanceMap(const cv::Mat& tsl, const SkinModel& model, cv::Mat* out);
// The same from the 8-bit BGR image, its TSL taken a row at a time (ForEachTslRow) instead of
// as a whole image: the same values, bit for bit, without the image's TSL (12 bytes a pixel).
void SkinDistanceMapOfBgr(const cv::Mat& bgr, const SkinModel& model, cv::Mat* out);

// Whether a region (a BIP colour region, a candidate target) is skin the attention stage may
// track as such: a face or a hand, not a brick wall, a lawn or a wooden door that happens to
// have skin chrominance. Every test must pass; each bound is documented in docs/SKIN.md
// ("Skin regions") with what it measured.
struct SkinRegionOptions {
  // A pixel is confident skin when d^2 < confident x T_s (0.5: the tpr:0.9 threshold of the
  // shipped model's data is 0.44 T_s; on the UCI data 0.5 T_s keeps 93 % of skin and 0.9 % of
  // non-skin pixels, against 99 % and 1.7 % at T_s).
  double confident = 0.5;
  double min_confident_share = 0.6;  // share of the region's pixels that are confident skin
  // The mean over the region of min(1, sqrt(d^2 / T_s)) (1 minus the soft skin map): skin
  // regions sit near the model's mean, surfaces that only graze the ellipse do not.
  double max_mean_distance = 0.6;
  // Shape: faces and hands are compact blobs. Solidity = area / area of the convex hull.
  double min_solidity = 0.6;
  double max_aspect_ratio = 3.5;    // long over short side of the minimum-area rectangle
  double max_area_fraction = 0.06;  // of the image: a face at arm's length is about 4 %
  int min_area = 30;                // px: fewer is noise, not a face or a hand
  // "" when valid; otherwise "KEY: what is wrong".
  std::string Check() const;
  // The fields (util/option_fields.h), which Check and the configuration apply.
  static const OptionFields<SkinRegionOptions>& Fields();
};

// The measurements behind the decision, and the first test that failed.
struct SkinRegionVerdict {
  bool skin = false;
  int area = 0;                  // pixels of the mask
  double confident_share = 0.0;  // 0..1
  double mean_distance = 1.0;    // 0..1
  double solidity = 0.0;         // 0..1
  double aspect_ratio = 0.0;     // >= 1
  double area_fraction = 0.0;    // of the image
  std::string failed;            // "" when skin; else the option whose bound failed
  std::string Describe() const;  // one line: the numbers and the verdict
};

// `mask`: CV_8UC1, non-zero on the region, the size of `distances` (SkinDistanceMap of the
// frame's TSL image) or of `tsl` (CV_32FC3). An empty region is not skin (failed: min_area).
// The attention stage calls the first once per candidate with the frame's distance map,
// computed once per frame; the second is the same decision from the TSL image.
SkinRegionVerdict JudgeSkinRegion(const cv::Mat& mask, const cv::Mat& distances, double threshold,
                                  const SkinRegionOptions& options);
SkinRegionVerdict JudgeSkinRegionTsl(const cv::Mat& mask, const cv::Mat& tsl,
                                     const SkinModel& model, const SkinRegionOptions& options);

// Each region's mean of `map` painted over its pixels (0 outside the mask). With `over`
// (CV_8UC1), the mean over the pixels it marks only (0 for a region with none of them).
void AverageOverRegions(const Segmentation& segmentation, cv::Mat* map,
                        const cv::Mat& over = cv::Mat());

// Parameters: SkinFeatureOptions::Fields().
std::unique_ptr<FeatureMap> CreateSkinFeature(const ParamBlock& params, const FeatureSetup& setup);

}  // namespace attend
