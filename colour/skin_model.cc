#include "colour/skin_model.h"

#include <Eigen/LU>
#include <algorithm>
#include <charconv>
#include <cmath>

#include "util/strings.h"

namespace attend {

namespace {

// The largest S of any colour, reached by pure red and pure green (|(r', g')| = sqrt(5) / 3).
constexpr double kMaxSaturation = 255.0;
// A covariance is degenerate when det <= kSingular * a * c, i.e. when the correlation of T and
// S is within 1e-12 of +-1 (all samples on a line).
constexpr double kSingular = 1e-12;

}  // namespace

SkinModelProblem FindSkinModelProblem(const SkinModel& model) {
  if (!model.mean.allFinite()) return {"mean", "must be finite numbers"};
  if (!(model.mean[0] >= 0.0 && model.mean[0] <= 1.0)) {
    return {"mean", "T = " + ShortestNumber(model.mean[0]) + " is outside [0, 1]"};
  }
  if (!(model.mean[1] >= 0.0 && model.mean[1] <= kMaxSaturation)) {
    return {"mean", "S = " + ShortestNumber(model.mean[1]) + " is outside [0, 255]"};
  }
  const Eigen::Matrix2d& c = model.covariance;
  if (!c.allFinite()) return {"covariance", "must be finite numbers"};
  // Relative to sqrt(a c), the largest off-diagonal a positive definite matrix can have.
  const double scale =
      std::max({std::abs(c(0, 1)), std::abs(c(1, 0)), std::sqrt(std::abs(c(0, 0) * c(1, 1)))});
  if (std::abs(c(0, 1) - c(1, 0)) > 1e-12 * scale) {
    return {"covariance", "is not symmetric: elements 1 and 2 (" + ShortestNumber(c(0, 1)) + ", " +
                              ShortestNumber(c(1, 0)) + ") differ"};
  }
  const double det = c(0, 0) * c(1, 1) - c(0, 1) * c(1, 0);
  if (!(c(0, 0) > 0.0 && c(1, 1) > 0.0 && det > kSingular * c(0, 0) * c(1, 1))) {
    return {"covariance", "is not positive definite (variances " + ShortestNumber(c(0, 0)) +
                              " and " + ShortestNumber(c(1, 1)) + ", determinant " +
                              ShortestNumber(det) + ")"};
  }
  if (!(std::isfinite(model.threshold) && model.threshold > 0.0)) {
    return {"threshold", "must be a finite number > 0, got " + ShortestNumber(model.threshold)};
  }
  return {};
}

double SkinModel::SquaredDistance(double t, double s) const {
  return SkinClassifier(*this).SquaredDistance(t, s);
}

std::string SkinModel::Check() const {
  const SkinModelProblem problem = FindSkinModelProblem(*this);
  return problem.key.empty() ? "" : problem.key + ": " + problem.message;
}

SkinClassifier::SkinClassifier(const SkinModel& model)
    : mean_t_(model.mean[0]), mean_s_(model.mean[1]), threshold_(model.threshold) {
  const Eigen::Matrix2d inverse = model.covariance.inverse();
  inverse_tt_ = inverse(0, 0);
  inverse_ts_ = 0.5 * (inverse(0, 1) + inverse(1, 0));
  inverse_ss_ = inverse(1, 1);
}

}  // namespace attend
