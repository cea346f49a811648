#include "features/skin_training.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "util/error.h"
#include "util/strings.h"

namespace attend {

namespace {

// The splitmix64 generator's output function (Steele, Lea and Flood 2014, with the constants
// of Vigna's splitmix64.c): a bijective 64-bit mixer, so consecutive indices hash apart.
uint64_t SplitMix64(uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

// The threshold between the last accepted squared distance and the first rejected one.
double ThresholdBetween(double accepted, double rejected) {
  if (std::isfinite(rejected)) {
    // Halfway; for adjacent doubles the midpoint may round onto `accepted`, which d < T rejects.
    const double middle = 0.5 * (accepted + rejected);
    return middle > accepted ? middle : rejected;
  }
  // Everything is accepted: a margin above the largest distance.
  return accepted + 1e-6 * std::max(1.0, accepted);
}

}  // namespace

bool IsHeldOut(uint64_t seed, uint64_t index, double fraction) {
  const uint64_t hash = SplitMix64(SplitMix64(seed) + index);
  // The top 53 bits as a double in [0, 1), exactly.
  const double u = static_cast<double>(hash >> 11) * 0x1.0p-53;
  return u < fraction;
}

void SkinSplit::Add(const cv::Vec2f& ts, bool skin) {
  SkinSamples& to = IsHeldOut(seed, next_index++, holdout_fraction) ? held_out : training;
  (skin ? to.skin : to.nonskin).push_back(ts);
}

SkinRates EvaluateSkinModel(const SkinModel& model, const SkinSamples& samples) {
  const SkinClassifier classifier(model);
  const auto accepted = [&](const std::vector<cv::Vec2f>& set) {
    int64_t count = 0;
    for (const cv::Vec2f& ts : set) count += classifier.IsSkin(ts[0], ts[1]) ? 1 : 0;
    return count;
  };
  SkinRates rates;
  rates.skin = static_cast<int64_t>(samples.skin.size());
  rates.nonskin = static_cast<int64_t>(samples.nonskin.size());
  rates.tpr = rates.skin > 0 ? static_cast<double>(accepted(samples.skin)) / rates.skin : -1.0;
  rates.fpr =
      rates.nonskin > 0 ? static_cast<double>(accepted(samples.nonskin)) / rates.nonskin : -1.0;
  return rates;
}

std::string ThresholdRule::Describe() const {
  return kind == Kind::kYouden ? "youden" : "tpr:" + ShortestNumber(target_tpr);
}

ThresholdRule ThresholdRule::Parse(const std::string& text) {
  ThresholdRule rule;
  if (text == "youden") return rule;
  if (text.rfind("tpr:", 0) == 0) {
    const std::string value = text.substr(4);
    double target = 0.0;
    const auto [end, status] = std::from_chars(value.data(), value.data() + value.size(), target);
    if (status == std::errc() && end == value.data() + value.size() && target > 0.0 &&
        target <= 1.0) {
      rule.kind = Kind::kTpr;
      rule.target_tpr = target;
      return rule;
    }
    throw ConfigError("threshold rule '" + text + "': the target TPR must be a number in (0, 1]");
  }
  throw ConfigError("threshold rule '" + text + "': expected youden or tpr:X with X in (0, 1]");
}

namespace {

// The Youden threshold over the sorted squared distances of the training samples (true: a skin
// sample): the one that maximises TPR - FPR.
double YoudenThreshold(const std::vector<std::pair<double, bool>>& distances, size_t n,
                       size_t nonskin) {
  const double infinity = std::numeric_limits<double>::infinity();
  double threshold = infinity;
  // Sweep the candidate thresholds: after each run of equal distances, everything up to it
  // is accepted. Ties in J keep the first, the smaller threshold.
  const double skin_count = static_cast<double>(n);
  const double nonskin_count = static_cast<double>(nonskin);
  int64_t true_positives = 0, false_positives = 0;
  double best_j = -infinity;
  for (size_t i = 0; i < distances.size(); ++i) {
    (distances[i].second ? true_positives : false_positives) += 1;
    const bool run_ends = i + 1 == distances.size() || distances[i + 1].first > distances[i].first;
    if (!run_ends) continue;
    const double j = true_positives / skin_count - false_positives / nonskin_count;
    if (j > best_j) {
      best_j = j;
      threshold = ThresholdBetween(distances[i].first,
                                   i + 1 < distances.size() ? distances[i + 1].first : infinity);
    }
  }
  return threshold;
}

// The threshold that accepts `target_tpr` of the skin samples (tpr:X).
double TprThreshold(const std::vector<std::pair<double, bool>>& distances, size_t n,
                    double target_tpr) {
  const double infinity = std::numeric_limits<double>::infinity();
  // The k-th nearest skin sample, k = ceil(target n), must be accepted. The small slack keeps
  // 0.95 * 40000 = 38000.000000000004 from asking for 38001.
  const int64_t k = std::clamp<int64_t>(static_cast<int64_t>(std::ceil(target_tpr * n - 1e-9)), 1,
                                        static_cast<int64_t>(n));
  int64_t seen = 0;
  size_t i = 0;
  for (; i < distances.size(); ++i) {
    if (distances[i].second && ++seen == k) break;
  }
  // Equal distances are accepted together; the threshold goes past the whole run.
  while (i + 1 < distances.size() && distances[i + 1].first == distances[i].first) ++i;
  return ThresholdBetween(distances[i].first,
                          i + 1 < distances.size() ? distances[i + 1].first : infinity);
}

}  // namespace

SkinModel FitSkinModel(const SkinSamples& training, const ThresholdRule& rule) {
  const size_t n = training.skin.size();
  if (n < 3) {
    throw InputError("the skin model needs at least 3 skin samples to fit, got " +
                     std::to_string(n));
  }
  if (rule.kind == ThresholdRule::Kind::kYouden && training.nonskin.empty()) {
    throw InputError(
        "the youden threshold rule needs non-skin samples, and the training split has none "
        "(use a tpr:X rule, or add non-skin samples)");
  }
  ATTEND_CHECK(rule.kind == ThresholdRule::Kind::kYouden ||
               (rule.target_tpr > 0.0 && rule.target_tpr <= 1.0))
      << "target TPR " << rule.target_tpr;

  // Maximum likelihood: the sample mean and the covariance normalised by n (not n - 1).
  SkinModel model;
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  for (const cv::Vec2f& ts : training.skin) sum += Eigen::Vector2d(ts[0], ts[1]);
  model.mean = sum / static_cast<double>(n);
  double tt = 0.0, ts_sum = 0.0, ss = 0.0;
  for (const cv::Vec2f& ts : training.skin) {
    const double dt = ts[0] - model.mean[0], ds = ts[1] - model.mean[1];
    tt += dt * dt;
    ts_sum += dt * ds;
    ss += ds * ds;
  }
  model.covariance << tt / n, ts_sum / n, ts_sum / n, ss / n;
  const SkinModelProblem problem = FindSkinModelProblem(model);
  if (!problem.key.empty()) {
    throw InputError("the skin samples cannot be modelled: their " + problem.key + " " +
                     problem.message + " (the samples must vary in both T and S)");
  }

  // Squared distances of every training sample, sorted, with their labels.
  const SkinClassifier classifier(model);
  std::vector<std::pair<double, bool>> distances;
  distances.reserve(n + training.nonskin.size());
  for (const cv::Vec2f& ts : training.skin) {
    distances.emplace_back(classifier.SquaredDistance(ts[0], ts[1]), true);
  }
  for (const cv::Vec2f& ts : training.nonskin) {
    distances.emplace_back(classifier.SquaredDistance(ts[0], ts[1]), false);
  }
  std::sort(distances.begin(), distances.end());

  model.threshold = rule.kind == ThresholdRule::Kind::kYouden
                        ? YoudenThreshold(distances, n, training.nonskin.size())
                        : TprThreshold(distances, n, rule.target_tpr);

  SkinModel::Provenance& provenance = model.provenance;
  provenance.rule = rule.Describe();
  provenance.skin_samples = static_cast<int64_t>(n);
  provenance.nonskin_samples = static_cast<int64_t>(training.nonskin.size());
  const SkinRates rates = EvaluateSkinModel(model, training);
  provenance.training_tpr = rates.tpr;
  provenance.training_fpr = rates.fpr;
  return model;
}

}  // namespace attend
