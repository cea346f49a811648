// Scanpaths to score beside a model's order of attention (docs/FIXATIONS.md, "Scanpaths"):
// fixations drawn around the centre of the image, and a saliency map's peaks in order of
// height, without inhibition of return.
#pragma once

#include <opencv2/core.hpp>

#include "eval/scanpath_metrics.h"

namespace attend {

// `count` fixations drawn independently from the centre bias of eval-fixations' `centre`
// baseline (CentreBias, eval/fixation_metrics.h): a Gaussian centred on the image with sigma
// `sigma_fraction` x width and height; a draw outside the image is drawn again. Each lasts
// `duration_s`. Deterministic for a given `rng` state.
Scanpath CentreBiasScanpath(cv::Size image, int count, double duration_s, cv::RNG* rng,
                            double sigma_fraction = 0.25);

// The peaks of `map` (one channel, any size; scaled to `image`'s pixels), highest first, at
// most `count`, each lasting `duration_s`. A peak is a pixel whose value is the largest within
// `separation` x the map's larger side (a square window: Chebyshev distance), and farther
// than that from every higher peak already taken (a plateau gives one peak, at its first pixel
// in raster order).
// There is no inhibition of return beyond that separation: the order is the order of height.
// A map has at least one peak, its maximum.
Scanpath SaliencyPeaks(const cv::Mat& map, cv::Size image, int count, double separation,
                       double duration_s);

}  // namespace attend
