// Scores of a saliency map against human eye fixations, as defined by Bylinskii, Judd, Oliva,
// Torralba and Durand, "What do different evaluation metrics tell us about saliency models?",
// TPAMI 2019 (sec. 3), following the conventions of the MIT saliency benchmark code.
//
// Maps are one-channel CV_32F or CV_64F matrices at the stimulus size (computed in double).
// A fixation is at pixel (round(x), round(y)) (halves away from zero, as MATLAB's round);
// fixations outside the map are ignored. Like the benchmark's binary fixation map, the
// location-based metrics (NSS, the AUCs, IG) count each fixated pixel once, however many
// fixations land on it; FixationDensity counts every fixation.
//
// Bad data (an empty or multi-channel map, maps of different sizes, no fixation inside the
// map) throws InputError naming the metric; bad parameters (splits, step, sigma) are caller
// bugs and fail an ATTEND_CHECK.
#pragma once

#include <cstdint>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "eval/fixation_data.h"

namespace attend {

// The fixation density: a Gaussian of `sigma` px at each fixation, i.e. cv::GaussianBlur of the
// fixation count map (kernel to 4 sigma, zero beyond the image), normalised to sum 1. CV_64F.
// Costs (rows with a fixation) x 8 sigma x width, not a full 2-D blur. Datasets usually
// take sigma as about one degree of visual angle (e.g. 0.025 x max(width, height)).
cv::Mat FixationDensity(cv::Size size, const std::vector<Fixation>& fixations, double sigma);

// Normalised scanpath saliency (sec. 3.2.1): the mean of the z-scored map (population standard
// deviation) at the fixated pixels; 0 for a constant map.
double Nss(const cv::Mat& map, const std::vector<Fixation>& fixations);

// AUC-Judd (sec. 3.1.1): the thresholds are the map's values at the fixated pixels, every other
// pixel is a negative, and the ROC curve's vertices are joined by straight lines. Fixated
// pixels of equal value form a single threshold, so ties count half: a constant map gives 0.5
// (the value the MIT code's random jitter gives on average, without the randomness).
double AucJudd(const cv::Mat& map, const std::vector<Fixation>& fixations);

// AUC-Borji (sec. 3.1.2): per split, as many negatives as fixated pixels drawn uniformly (with
// replacement) from all pixels; thresholds from the range-normalised map's maximum down to 0 in
// `step`s; the mean AUC over `splits`. Deterministic for a given `seed`.
double AucBorji(const cv::Mat& map, const std::vector<Fixation>& fixations, int splits = 100,
                double step = 0.1, uint64_t seed = 1);

// Shuffled AUC (sec. 3.1.3): as AucBorji, but the negatives are drawn without replacement from
// the pixels fixated in other images (`other_fixations`, already in this image's coordinates:
// the caller scales them), min(#fixated, #other) per split. Penalises a pure centre bias.
// As in the MIT code the other fixations form a binary map, so where many of them share a
// pixel (a crowded centre at low resolution) that pixel is drawn no more often than any other.
double ShuffledAuc(const cv::Mat& map, const std::vector<Fixation>& fixations,
                   const std::vector<Fixation>& other_fixations, int splits = 100,
                   double step = 0.1, uint64_t seed = 1);

// Pearson's correlation coefficient between the map and the fixation density (sec. 3.2.3);
// 0 when either map is constant.
double Cc(const cv::Mat& map, const cv::Mat& density);

// KL(density || map) in nats (sec. 3.2.4), both normalised to sum 1, with the MIT code's
// eps = 2.2204e-16: sum density * log(eps + density / (map + eps)). A map with negative values
// is first shifted to a minimum of 0; a map that sums to 0 is taken as uniform.
double Kl(const cv::Mat& map, const cv::Mat& density);

// Similarity (sec. 3.2.2): the histogram intersection sum min(p, q) of the two maps, each
// range-normalised to [0, 1] and then to sum 1 (a constant map is taken as uniform).
double Sim(const cv::Mat& map, const cv::Mat& density);

// Information gain over `baseline` (sec. 3.2.5) in bits per fixated pixel: both maps are
// turned into distributions over pixels (range-normalised to [0, 1], + eps, sum 1; a constant
// map becomes uniform) and IG = mean over fixated pixels of log2(p_map + eps) -
// log2(p_baseline + eps).
double InformationGain(const cv::Mat& map, const cv::Mat& baseline,
                       const std::vector<Fixation>& fixations);

// A centre-bias map: a Gaussian centred on the image with sigma_x = sigma_fraction x width and
// sigma_y = sigma_fraction x height, scaled to a maximum of 1. CV_64F. The default 0.25 puts
// the image's corners at about 2.8 sigma (radially); a typical baseline for InformationGain.
cv::Mat CentreBias(cv::Size size, double sigma_fraction = 0.25);

// The mean of `values` and its 95 % confidence interval by the normal approximation,
// mean +- 1.96 x sd / sqrt(n) with the sample (n - 1) standard deviation. With one value the
// interval is the value itself. `values` must not be empty.
struct MeanInterval {
  double mean = 0.0;
  double low = 0.0;
  double high = 0.0;
  int n = 0;
};
MeanInterval MeanWithInterval(const std::vector<double>& values);

// Every metric of one map; the order of the fields is that of FixationMetricNames().
struct FixationScores {
  double nss = 0.0;
  double auc_judd = 0.0;
  double auc_borji = 0.0;
  double sauc = 0.0;
  double cc = 0.0;
  double kl = 0.0;
  double sim = 0.0;
  double ig = 0.0;
};

// All metrics with their default parameters: `density` is FixationDensity of `fixations`,
// `baseline` the map InformationGain compares against, `other_fixations` ShuffledAuc's negatives.
FixationScores ScoreMap(const cv::Mat& map, const std::vector<Fixation>& fixations,
                        const std::vector<Fixation>& other_fixations, const cv::Mat& density,
                        const cv::Mat& baseline);

// {"nss", "auc_judd", "auc_borji", "sauc", "cc", "kl", "sim", "ig"}: CSV columns, in order.
const std::vector<std::string>& FixationMetricNames();

// The score called `name` (one of FixationMetricNames()); ConfigError for another name.
double Get(const FixationScores& scores, const std::string& name);

}  // namespace attend
