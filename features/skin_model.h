// The skin chrominance model of thesis 5.1.1 (after Terrillon and Akamatsu): a Gaussian over
// the TSL chrominance (T, S) of skin pixels, with mean m_s and covariance C_s; a pixel is skin
// iff its squared Mahalanobis distance to m_s is below T_s (SPEC 2.3). This file holds the
// model, its YAML file, its training from labelled samples and its evaluation (docs/SKIN.md).
// T is in [0, 1), S in [0, 255] (colour/colour.h).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace attend {

struct SkinModel {
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();            // m_s over (T, S)
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Identity();  // C_s, symmetric positive definite
  double threshold = 1.0;  // T_s, on the squared Mahalanobis distance

  // How the model was made (written to and read from the model file; informative only).
  struct Provenance {
    std::string command;       // the skin-train invocation
    std::string data;          // the training data as given to skin-train
    std::string rule;          // how the threshold was chosen
    int64_t skin_samples = 0;  // samples the model was fitted on (the training split)
    int64_t nonskin_samples = 0;
    double holdout_fraction = 0.0;
    uint64_t seed = 0;
    double training_tpr = -1.0;  // rates on the training split; < 0 when unknown
    double training_fpr = -1.0;
    double holdout_tpr = -1.0;  // rates on the held-out split; < 0 when unknown
    double holdout_fpr = -1.0;
  } provenance;

  // Squared Mahalanobis distance of a chrominance to the mean. Inverts the covariance on each
  // call; SkinClassifier inverts it once, for many pixels, with the same arithmetic.
  double SquaredDistance(double t, double s) const;
  bool IsSkin(double t, double s) const { return SquaredDistance(t, s) < threshold; }

  // "" when valid; otherwise "KEY: what is wrong" (covariance not symmetric positive definite,
  // mean outside the TSL range, threshold <= 0, non-finite numbers).
  std::string Check() const;
};

// The decision of a valid model (Check() empty) with the inverse covariance computed once.
// Gives exactly the distances of SkinModel::SquaredDistance.
class SkinClassifier {
 public:
  explicit SkinClassifier(const SkinModel& model);
  double SquaredDistance(double t, double s) const {
    const double dt = t - mean_t_, ds = s - mean_s_;
    return inverse_tt_ * dt * dt + 2.0 * inverse_ts_ * dt * ds + inverse_ss_ * ds * ds;
  }
  bool IsSkin(double t, double s) const { return SquaredDistance(t, s) < threshold_; }

 private:
  double mean_t_, mean_s_;
  double inverse_tt_, inverse_ts_, inverse_ss_;  // C_s^-1, symmetric
  double threshold_;
};

// Reads a model file (keys: mean [t, s]; covariance [a, b, b, c] row-major; threshold; and an
// optional `training:` block with the provenance). Missing file, missing key, unknown key,
// wrong type or an invalid model: ConfigError naming the file, key and line.
SkinModel LoadSkinModel(const std::string& path);
// Writes the model as YAML with comments that say what each key means, every number written
// so that it reads back exactly. The file is written beside `path` and renamed into place, so
// `path` is never left half-written. OutputError when the file cannot be written.
void SaveSkinModel(const SkinModel& model, const std::string& path);

// Labelled chrominance samples.
struct SkinSamples {
  std::vector<cv::Vec2f> skin;     // (T, S)
  std::vector<cv::Vec2f> nonskin;  // (T, S)
};

// Receives samples one at a time, in the order they are read.
using SkinSampleSink = std::function<void(const cv::Vec2f& ts, bool skin)>;

// Appends the samples of the `B G R label` text format (label 1 skin, 2 not skin; the UCI Skin
// Segmentation data set): one sample a line, four integers separated by spaces or tabs, blank
// lines ignored. A malformed line: InputError naming the file and line; a file without
// samples: InputError.
void ReadSkinText(const std::string& path, SkinSamples* samples);
void ReadSkinText(const std::string& path, const SkinSampleSink& sink);
// Appends every pixel of an 8-bit colour image with its mask (read as grey, non-zero = skin),
// in raster order. Unreadable files or different sizes: InputError naming the file.
void ReadSkinImagePair(const std::string& image_path, const std::string& mask_path,
                       SkinSamples* samples);
void ReadSkinImagePair(const std::string& image_path, const std::string& mask_path,
                       const SkinSampleSink& sink);

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
