// The skin chrominance model of thesis 5.1.1 (after Terrillon and Akamatsu): a Gaussian over
// the TSL chrominance (T, S) of skin pixels, with mean m_s and covariance C_s; a pixel is skin
// iff its squared Mahalanobis distance to m_s is below T_s (SPEC 2.3). T is in [0, 1), S in
// [0, 255] (colour/colour.h). Its file is read and written in io/skin_files.h, its training
// and evaluation are in features/skin_training.h (docs/SKIN.md).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>

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

// What is wrong with a model, and under which key of its file (`key` empty: nothing).
struct SkinModelProblem {
  std::string key;
  std::string message;
};
SkinModelProblem FindSkinModelProblem(const SkinModel& model);

}  // namespace attend
