// Training and evaluating the skin model (colour/skin_model.h) from labelled samples
// (io/skin_files.h), as `attend skin-train` does (docs/SKIN.md).
#pragma once

#include <cstdint>
#include <opencv2/core.hpp>
#include <string>

#include "colour/skin_model.h"
#include "io/skin_files.h"

namespace attend {

// A deterministic split: sample `index` of a data set is held out iff a hash of (seed, index)
// falls below `fraction`. The same data, seed and fraction always give the same split, on any
// machine: u = splitmix64(splitmix64(seed) + index) / 2^64 (top 53 bits), held out iff
// u < fraction.
bool IsHeldOut(uint64_t seed, uint64_t index, double fraction);

// Splits samples as they arrive: the n-th sample added (n = 0, 1, ... over every data set fed
// to it, in order) goes to `held_out` iff IsHeldOut(seed, n, holdout_fraction).
struct SkinSplit {
  uint64_t seed = 1;
  double holdout_fraction = 0.2;
  SkinSamples training;
  SkinSamples held_out;
  uint64_t next_index = 0;

  void Add(const cv::Vec2f& ts, bool skin);
  // A sink that adds to this split (which must outlive it).
  SkinSampleSink Sink() {
    return [this](const cv::Vec2f& ts, bool skin) { Add(ts, skin); };
  }
};

struct SkinRates {
  double tpr = 0.0;  // skin samples classified as skin; -1 when there are none
  double fpr = 0.0;  // non-skin samples classified as skin; -1 when there are none
  int64_t skin = 0;
  int64_t nonskin = 0;
};
SkinRates EvaluateSkinModel(const SkinModel& model, const SkinSamples& samples);

// How the threshold is chosen from the training samples. Both rules sort the squared
// distances of the training samples and put the threshold halfway between the last accepted
// and the first rejected distance.
struct ThresholdRule {
  enum class Kind {
    kYouden,  // maximise TPR - FPR on the training split (default); ties: the smaller threshold
    kTpr,     // the smallest threshold that accepts at least `target_tpr` of the skin samples
  } kind = Kind::kYouden;
  double target_tpr = 0.95;      // in (0, 1]
  std::string Describe() const;  // "youden", "tpr:0.95"
  // Reads "youden" or "tpr:X" with X in (0, 1]; anything else: ConfigError.
  static ThresholdRule Parse(const std::string& text);
};

// Fits mean and covariance to the skin samples (maximum likelihood) and chooses the threshold
// by `rule` (which needs non-skin samples for kYouden). Fewer than 3 skin samples, a
// degenerate covariance or kYouden without non-skin samples: InputError. Fills the
// provenance's rule, sample counts and training rates.
SkinModel FitSkinModel(const SkinSamples& training, const ThresholdRule& rule);

}  // namespace attend
