// The saliency map (thesis 5.1.1.2, SPEC 2.3): every feature map is normalised to [0, 1],
// multiplied by its weight, summed, and divided by the sum of weights.
//
// The built-in normalisations (their table is saliency/normalisation.h):
// - minmax (SPEC, default): (F - min) / (max - min) over the frame; a constant map becomes 0.
// - local_maxima: Itti, Koch and Niebur's N(.) (PAMI 20(11), 1998): the min-max map times
//   (1 - m)^2, with m the mean of the map's local maxima other than the global one. A map with
//   one strong peak keeps it; a map with many comparable peaks is suppressed. A local maximum
//   is a connected plateau of pixels that equal the maximum of their window, counted once
//   whatever its area (region-based features are piecewise constant).
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "saliency/saliency_options.h"

namespace attend {

// Normalises `map` (CV_32FC1) into `out` (CV_32FC1, [0, 1]) by the built-in normalisation
// `options.normalisation` (minmax for a name that is not built in).
void NormaliseMap(const cv::Mat& map, const SaliencyOptions& options, cv::Mat* out);

// sum_i weights[i] * normalised[i] / sum_i weights[i], CV_32FC1. No maps, or weights summing to
// 0, give a zero map of `size`.
void CombineMaps(const std::vector<cv::Mat>& normalised, const std::vector<double>& weights,
                 cv::Size size, cv::Mat* out);

// The weighted geometric mean of the maps as `combination` "product" defines it (CV_32FC1,
// [0, 1]); no maps, or weights summing to 0, give a zero map of `size`. The maps marked in
// `additive` (empty: none) are not factors: with W_g the weights of the others, G their
// geometric mean and W the sum of all weights, the map is (W_g G + sum_a w_a n_a) / W.
void MultiplyMaps(const std::vector<cv::Mat>& normalised, const std::vector<double>& weights,
                  const std::vector<bool>& additive, cv::Size size, cv::Mat* out);

// Blurs `map` (CV_32FC1, [0, 1]) in place as `options.blur` says (nothing when it is 0), then,
// when `options.gamma` is not 1, scales it to a maximum of 1 and raises it to that power.
void SmoothSaliency(const SaliencyOptions& options, cv::Mat* map);

}  // namespace attend
