// What a target keeps of its looks from frame to frame (the bounded mode; docs/TRACKING.md,
// "Modes" 8, 10, 11), and the colour bins its statistics use. AppearanceModel
// (appearance_model.h) learns and matches it. Not part of the API.
#pragma once

#include <algorithm>
#include <opencv2/core.hpp>
#include <vector>

namespace attend {
namespace tracker_internal {

// The grey standard deviation below which a target's appearance model is taken as flat.
inline constexpr double kMinAppearanceDeviation = 10.0;

// Bins of the HSV cylinder for the colour statistics: 32 units a side on each axis (S cos H and
// S sin H in [-255, 255], V in [0, 255]).
inline constexpr int kChromaBins = 16, kValueBins = 8;
inline constexpr int kColourBins = kChromaBins * kChromaBins * kValueBins;
inline int ColourBin(const float* f) {
  const int bx = std::clamp(static_cast<int>((f[0] + 256.f) / 32.f), 0, kChromaBins - 1);
  const int by = std::clamp(static_cast<int>((f[1] + 256.f) / 32.f), 0, kChromaBins - 1);
  const int bv = std::clamp(static_cast<int>(f[2] / 32.f), 0, kValueBins - 1);
  return (bx * kChromaBins + by) * kValueBins + bv;
}

// One target's looks. Empty in the thesis mode.
struct TargetAppearance {
  // Per colour bin, the share of the target's pixels among the target's and its surroundings'
  // (each normalised by its count); empty: every template weight counts wholly.
  std::vector<float> distinct;
  // The grey model of the box (CV_32FC1, the first box's size); empty for a flat first box.
  cv::Mat grey;
  bool judged = false;  // whether the first box was judged for texture
  // Running means of the correlation the model had, and of the mean distinctiveness of the
  // box (MeanDistinct), where the target was found.
  double typical_correlation = 0.0;
  double typical_distinct = 0.0;
};

}  // namespace tracker_internal
}  // namespace attend
