// The skin chrominance model of thesis 5.1.1 (after Terrillon and Akamatsu): a Gaussian over
// the TSL chrominance (T, S) of skin pixels, with mean m_s and covariance C_s; a pixel is skin
// iff its squared Mahalanobis distance to m_s is below T_s (SPEC 2.3). This file holds the
// model, its YAML file, its training from labelled samples and its evaluation.
// T is in [0, 1), S in [0, 255] (colour/colour.h).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace attend {

struct SkinModel {
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();         // m_s over (T, S)
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Identity();  // C_s, symmetric positive definite
  double threshold = 1.0;  // T_s, on the squared Mahalanobis distance

  // How the model was made (written to and read from the model file; informative only).
  struct Provenance {
    std::string data;      // the training data as given to skin-train
    std::string rule;      // how the threshold was chosen
    int64_t skin_samples = 0;
    int64_t nonskin_samples = 0;
    double holdout_fraction = 0.0;
    uint64_t seed = 0;
    double holdout_tpr = -1.0;  // rates on the held-out split; < 0 when unknown
    double holdout_fpr = -1.0;
  } provenance;

  // Squared Mahalanobis distance of a chrominance to the mean.
  double SquaredDistance(double t, double s) const;
  bool IsSkin(double t, double s) const { return SquaredDistance(t, s) < threshold; }

  // "" when valid; otherwise what is wrong (covariance not symmetric positive definite,
  // threshold <= 0, non-finite numbers).
  std::string Check() const;
};

// Reads a model file (keys: mean [t, s]; covariance [a, b, b, c] row-major; threshold; and an
// optional `training:` block with the provenance). Missing file, missing key, wrong type or an
// invalid model: ConfigError naming the file, key and line.
SkinModel LoadSkinModel(const std::string& path);
// Writes the model as YAML with comments that say what each key means. OutputError when the
// file cannot be written.
void SaveSkinModel(const SkinModel& model, const std::string& path);

// Labelled chrominance samples.
struct SkinSamples {
  std::vector<cv::Vec2f> skin;     // (T, S)
  std::vector<cv::Vec2f> nonskin;  // (T, S)
};

// Appends the samples of the `B G R label` text format (label 1 skin, 2 not skin; the UCI Skin
// Segmentation data set). A malformed line: InputError naming the file and line.
void ReadSkinText(const std::string& path, SkinSamples* samples);
// Appends every pixel of an 8-bit colour image with its mask (non-zero = skin). Unreadable
// files or different sizes: InputError naming the file.
void ReadSkinImagePair(const std::string& image_path, const std::string& mask_path,
                       SkinSamples* samples);

// A deterministic split: sample `index` of a data set is held out iff a hash of (seed, index)
// falls below `fraction`. The same data, seed and fraction always give the same split.
bool IsHeldOut(uint64_t seed, uint64_t index, double fraction);

struct SkinRates {
  double tpr = 0.0;  // skin samples classified as skin
  double fpr = 0.0;  // non-skin samples classified as skin
  int64_t skin = 0;
  int64_t nonskin = 0;
};
SkinRates EvaluateSkinModel(const SkinModel& model, const SkinSamples& samples);

// How the threshold is chosen from the training samples.
struct ThresholdRule {
  enum class Kind {
    kYouden,  // maximise TPR - FPR on the training split (default)
    kTpr,     // the smallest threshold that accepts at least `target_tpr` of the skin samples
  } kind = Kind::kYouden;
  double target_tpr = 0.95;
  std::string Describe() const;  // "youden", "tpr:0.95"
};

// Fits mean and covariance to the skin samples (maximum likelihood) and chooses the threshold
// by `rule` (which needs non-skin samples for kYouden). Fewer than 3 skin samples or a
// degenerate covariance: InputError.
SkinModel FitSkinModel(const SkinSamples& training, const ThresholdRule& rule);

}  // namespace attend
