#include "features/skin_model.h"

#include <unistd.h>
#include <yaml-cpp/yaml.h>

#include <Eigen/LU>
#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <opencv2/imgcodecs.hpp>
#include <sstream>
#include <system_error>
#include <utility>

#include "colour/colour.h"
#include "config/param_block.h"
#include "io/image_file.h"
#include "util/error.h"

namespace attend {

namespace {

namespace fs = std::filesystem;

// The largest S of any colour, reached by pure red and pure green (|(r', g')| = sqrt(5) / 3).
constexpr double kMaxSaturation = 255.0;
// A covariance is degenerate when det <= kSingular * a * c, i.e. when the correlation of T and
// S is within 1e-12 of +-1 (all samples on a line).
constexpr double kSingular = 1e-12;

// What is wrong with a model, and under which key of its file.
struct Problem {
  std::string key;
  std::string message;
};

std::string Number(double value) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  return std::string(buffer, result.ptr);
}

Problem FindProblem(const SkinModel& model) {
  if (!model.mean.allFinite()) return {"mean", "must be finite numbers"};
  if (!(model.mean[0] >= 0.0 && model.mean[0] <= 1.0)) {
    return {"mean", "T = " + Number(model.mean[0]) + " is outside [0, 1]"};
  }
  if (!(model.mean[1] >= 0.0 && model.mean[1] <= kMaxSaturation)) {
    return {"mean", "S = " + Number(model.mean[1]) + " is outside [0, 255]"};
  }
  const Eigen::Matrix2d& c = model.covariance;
  if (!c.allFinite()) return {"covariance", "must be finite numbers"};
  // Relative to sqrt(a c), the largest off-diagonal a positive definite matrix can have.
  const double scale =
      std::max({std::abs(c(0, 1)), std::abs(c(1, 0)), std::sqrt(std::abs(c(0, 0) * c(1, 1)))});
  if (std::abs(c(0, 1) - c(1, 0)) > 1e-12 * scale) {
    return {"covariance", "is not symmetric: elements 1 and 2 (" + Number(c(0, 1)) + ", " +
                              Number(c(1, 0)) + ") differ"};
  }
  const double det = c(0, 0) * c(1, 1) - c(0, 1) * c(1, 0);
  if (!(c(0, 0) > 0.0 && c(1, 1) > 0.0 && det > kSingular * c(0, 0) * c(1, 1))) {
    return {"covariance", "is not positive definite (variances " + Number(c(0, 0)) + " and " +
                              Number(c(1, 1)) + ", determinant " + Number(det) + ")"};
  }
  if (!(std::isfinite(model.threshold) && model.threshold > 0.0)) {
    return {"threshold", "must be a finite number > 0, got " + Number(model.threshold)};
  }
  return {};
}

// The splitmix64 generator's output function (Steele, Lea and Flood 2014, with the constants
// of Vigna's splitmix64.c): a bijective 64-bit mixer, so consecutive indices hash apart.
uint64_t SplitMix64(uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

std::string Quoted(const std::string& text) {
  YAML::Emitter out;
  out << YAML::DoubleQuoted << text;
  return out.c_str();
}

// What the rule in a model file means, for the file's comments.
std::string ExplainRule(const std::string& rule) {
  if (rule == "youden") return "youden: Youden's J, it maximises TPR - FPR on the training split";
  if (rule.rfind("tpr:", 0) == 0) {
    return rule + ": the smallest threshold accepting at least " + rule.substr(4) +
           " of the training skin samples";
  }
  return rule.empty() ? "not recorded" : rule;
}

// Reads a non-negative integer written as a YAML scalar (ParamBlock reads ints only).
uint64_t GetCount(const ParamBlock& block, const std::string& key, uint64_t max) {
  const std::string text = block.GetString(key, "0");
  uint64_t value = 0;
  const auto [end, status] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (status != std::errc() || end != text.data() + text.size() || value > max) {
    block.Fail(key, "expected an integer in [0, " + std::to_string(max) + "], got '" + text + "'");
  }
  return value;
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

cv::Mat ReadTrainingImage(const std::string& path, int flags, const char* what) {
  std::error_code error;
  if (!fs::is_regular_file(path, error)) throw InputError(path + ": no such " + what + " file");
  return ReadImageFile(path, flags, path);
}

// One line of text for a message: at most 60 characters, unprintable bytes shown as '?'.
std::string Excerpt(const char* begin, const char* end) {
  std::string text(begin, std::min<size_t>(end - begin, 60));
  for (char& c : text) {
    if (static_cast<unsigned char>(c) < 32 || static_cast<unsigned char>(c) > 126) c = '?';
  }
  if (end - begin > 60) text += "...";
  return text;
}

bool IsBlank(char c) { return c == ' ' || c == '\t'; }

}  // namespace

double SkinModel::SquaredDistance(double t, double s) const {
  return SkinClassifier(*this).SquaredDistance(t, s);
}

std::string SkinModel::Check() const {
  const Problem problem = FindProblem(*this);
  return problem.key.empty() ? "" : problem.key + ": " + problem.message;
}

SkinClassifier::SkinClassifier(const SkinModel& model)
    : mean_t_(model.mean[0]), mean_s_(model.mean[1]), threshold_(model.threshold) {
  const Eigen::Matrix2d inverse = model.covariance.inverse();
  inverse_tt_ = inverse(0, 0);
  inverse_ts_ = 0.5 * (inverse(0, 1) + inverse(1, 0));
  inverse_ss_ = inverse(1, 1);
}

SkinModel LoadSkinModel(const std::string& path) {
  const ParamBlock block = ParamBlock::LoadFile(path);
  SkinModel model;
  const std::vector<double> mean = block.GetDoubles("mean", {}, Range::Any(), 2);
  const std::vector<double> covariance = block.GetDoubles("covariance", {}, Range::Any(), 4);
  model.threshold = block.GetDouble("threshold", 0.0);

  const ParamBlock training = block.Child("training");
  SkinModel::Provenance& provenance = model.provenance;
  provenance.command = training.GetString("command", "");
  provenance.data = training.GetString("data", "");
  provenance.rule = training.GetString("rule", "");
  constexpr uint64_t kMaxCount = std::numeric_limits<int64_t>::max();
  provenance.skin_samples = static_cast<int64_t>(GetCount(training, "skin_samples", kMaxCount));
  provenance.nonskin_samples =
      static_cast<int64_t>(GetCount(training, "nonskin_samples", kMaxCount));
  provenance.holdout_fraction =
      training.GetDouble("holdout_fraction", 0.0, {0.0, 1.0, false, true});
  provenance.seed = GetCount(training, "seed", std::numeric_limits<uint64_t>::max());
  const Range rate = Range::Closed(0.0, 1.0);
  provenance.training_tpr = training.GetDouble("training_tpr", -1.0, rate);
  provenance.training_fpr = training.GetDouble("training_fpr", -1.0, rate);
  provenance.holdout_tpr = training.GetDouble("holdout_tpr", -1.0, rate);
  provenance.holdout_fpr = training.GetDouble("holdout_fpr", -1.0, rate);
  training.CheckNoUnknownKeys();
  block.CheckNoUnknownKeys();

  for (const char* key : {"mean", "covariance", "threshold"}) {
    if (!block.Has(key)) block.Fail(key, "required key is missing");
  }
  model.mean = Eigen::Vector2d(mean[0], mean[1]);
  model.covariance << covariance[0], covariance[1], covariance[2], covariance[3];
  const Problem problem = FindProblem(model);
  if (!problem.key.empty()) block.Fail(problem.key, problem.message);
  return model;
}

void SaveSkinModel(const SkinModel& model, const std::string& path) {
  const std::string problem = model.Check();
  ATTEND_CHECK(problem.empty()) << "saving an invalid skin model: " << problem;
  const SkinModel::Provenance& p = model.provenance;
  const Eigen::Matrix2d& c = model.covariance;

  std::ostringstream text;
  text << "# attend skin colour model (SPEC 2.3, thesis 5.1.1, docs/SKIN.md): a Gaussian over the\n"
          "# TSL chrominance x = (T, S) of skin pixels, T in [0, 1), S in [0, 255]. A pixel is\n"
          "# skin iff (x - mean)^T covariance^-1 (x - mean) < threshold.\n"
       << "mean: [" << Number(model.mean[0]) << ", " << Number(model.mean[1]) << "]\n"
       << "# Row-major 2x2: [var T, cov(T, S), cov(T, S), var S].\n"
       << "covariance: [" << Number(c(0, 0)) << ", " << Number(c(0, 1)) << ", " << Number(c(1, 0))
       << ", " << Number(c(1, 1)) << "]\n"
       << "# T_s on the squared Mahalanobis distance, chosen by the rule training.rule:\n"
       << "# " << ExplainRule(p.rule) << ".\n"
       << "threshold: " << Number(model.threshold) << "\n"
       << "# How the model was made; informative only. Sample counts and training rates are of\n"
          "# the training split; held-out rates of the samples that the split set aside.\n"
       << "training:\n"
       << "  command: " << Quoted(p.command) << "\n"
       << "  data: " << Quoted(p.data) << "\n"
       << "  rule: " << Quoted(p.rule) << "\n"
       << "  holdout_fraction: " << Number(p.holdout_fraction) << "\n"
       << "  seed: " << p.seed << "\n"
       << "  skin_samples: " << p.skin_samples << "\n"
       << "  nonskin_samples: " << p.nonskin_samples << "\n";
  const std::pair<const char*, double> rates[] = {{"training_tpr", p.training_tpr},
                                                  {"training_fpr", p.training_fpr},
                                                  {"holdout_tpr", p.holdout_tpr},
                                                  {"holdout_fpr", p.holdout_fpr}};
  for (const auto& [key, value] : rates) {
    if (value >= 0.0) text << "  " << key << ": " << Number(value) << "\n";
  }

  // Written beside the target and renamed over it: a reader sees the old file or the new one.
  const fs::path target(path);
  std::ostringstream temporary_name;
  temporary_name << "." << target.filename().string() << ".tmp-" << getpid();
  const fs::path temporary = target.parent_path() / temporary_name.str();
  {
    std::ofstream file(temporary, std::ios::binary | std::ios::trunc);
    file << text.str();
    file.close();
    if (!file) {
      std::error_code ignored;
      fs::remove(temporary, ignored);
      throw OutputError(path + ": cannot write the model file");
    }
  }
  std::error_code error;
  fs::rename(temporary, target, error);
  if (error) {
    std::error_code ignored;
    fs::remove(temporary, ignored);
    throw OutputError(path + ": cannot write the model file (" + error.message() + ")");
  }
}

void ReadSkinText(const std::string& path, SkinSamples* samples) {
  ReadSkinText(path, [samples](const cv::Vec2f& ts, bool skin) {
    (skin ? samples->skin : samples->nonskin).push_back(ts);
  });
}

void ReadSkinText(const std::string& path, const SkinSampleSink& sink) {
  std::error_code error;
  if (fs::is_directory(path, error)) throw InputError(path + ": is a folder, not a text file");
  std::ifstream file(path, std::ios::binary);
  if (!file) throw InputError(path + ": cannot read the file (missing or not readable)");
  // The whole file at once, parsed in place: the UCI file (3 MB) reads in a few milliseconds.
  const std::string text((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  if (file.bad()) throw InputError(path + ": read error");

  const char* p = text.data();
  const char* const end = text.data() + text.size();
  int64_t line = 0;
  int64_t samples = 0;
  while (p < end) {
    ++line;
    const char* const line_begin = p;
    const char* line_end = static_cast<const char*>(memchr(p, '\n', end - p));
    if (line_end == nullptr) line_end = end;
    const char* content_end = line_end;
    if (content_end > line_begin && content_end[-1] == '\r') --content_end;
    p = line_end + 1;

    const char* q = line_begin;
    while (q < content_end && IsBlank(*q)) ++q;
    if (q == content_end) continue;  // a blank line

    int values[4];
    bool ok = true;
    for (int i = 0; i < 4 && ok; ++i) {
      if (i > 0) {
        const char* const before = q;
        while (q < content_end && IsBlank(*q)) ++q;
        ok = q > before;
      }
      const auto [next, status] = std::from_chars(q, content_end, values[i]);
      ok = ok && status == std::errc() && (next == content_end || IsBlank(*next));
      q = next;
    }
    while (ok && q < content_end && IsBlank(*q)) ++q;
    ok = ok && q == content_end;
    for (int i = 0; i < 3 && ok; ++i) ok = values[i] >= 0 && values[i] <= 255;
    ok = ok && (values[3] == 1 || values[3] == 2);
    if (!ok) {
      throw InputError(path + ":" + std::to_string(line) +
                       ": expected 'B G R label' (B, G, R in 0..255; label 1 skin, 2 not skin), "
                       "got '" +
                       Excerpt(line_begin, content_end) +
                       "' (an image with its mask is given as IMAGE:MASK)");
    }
    // The file holds B G R; TSL takes R, G, B.
    sink(TslChrominance(values[2], values[1], values[0]), values[3] == 1);
    ++samples;
  }
  if (samples == 0) throw InputError(path + ": holds no samples ('B G R label' lines)");
}

void ReadSkinImagePair(const std::string& image_path, const std::string& mask_path,
                       SkinSamples* samples) {
  ReadSkinImagePair(image_path, mask_path, [samples](const cv::Vec2f& ts, bool skin) {
    (skin ? samples->skin : samples->nonskin).push_back(ts);
  });
}

void ReadSkinImagePair(const std::string& image_path, const std::string& mask_path,
                       const SkinSampleSink& sink) {
  // IMREAD_COLOR gives 8-bit BGR whatever the file holds. The mask is read as grey at its own
  // depth, so that a 16-bit mask with small values is not scaled to zero.
  const cv::Mat bgr = ReadTrainingImage(image_path, cv::IMREAD_COLOR, "image");
  const cv::Mat mask = ReadTrainingImage(mask_path, cv::IMREAD_GRAYSCALE | cv::IMREAD_ANYDEPTH, "mask");
  if (mask.size() != bgr.size()) {
    throw InputError(mask_path + ": the mask is " + std::to_string(mask.cols) + "x" +
                     std::to_string(mask.rows) + " but its image " + image_path + " is " +
                     std::to_string(bgr.cols) + "x" + std::to_string(bgr.rows));
  }
  cv::Mat skin;
  cv::compare(mask, 0, skin, cv::CMP_NE);
  cv::Mat tsl;
  BgrToTsl(bgr, &tsl);
  for (int row = 0; row < tsl.rows; ++row) {
    const cv::Vec3f* pixel = tsl.ptr<cv::Vec3f>(row);
    const uchar* label = skin.ptr<uchar>(row);
    for (int col = 0; col < tsl.cols; ++col) {
      sink(cv::Vec2f(pixel[col][0], pixel[col][1]), label[col] != 0);
    }
  }
}

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
  return kind == Kind::kYouden ? "youden" : "tpr:" + Number(target_tpr);
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
  const Problem problem = FindProblem(model);
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
  const double infinity = std::numeric_limits<double>::infinity();

  if (rule.kind == ThresholdRule::Kind::kYouden) {
    // Sweep the candidate thresholds: after each run of equal distances, everything up to it
    // is accepted. Ties in J keep the first, the smaller threshold.
    const double skin_count = static_cast<double>(n);
    const double nonskin_count = static_cast<double>(training.nonskin.size());
    int64_t true_positives = 0, false_positives = 0;
    double best_j = -infinity;
    for (size_t i = 0; i < distances.size(); ++i) {
      (distances[i].second ? true_positives : false_positives) += 1;
      const bool run_ends =
          i + 1 == distances.size() || distances[i + 1].first > distances[i].first;
      if (!run_ends) continue;
      const double j = true_positives / skin_count - false_positives / nonskin_count;
      if (j > best_j) {
        best_j = j;
        model.threshold = ThresholdBetween(
            distances[i].first, i + 1 < distances.size() ? distances[i + 1].first : infinity);
      }
    }
  } else {
    // The k-th nearest skin sample, k = ceil(target n), must be accepted. The small slack keeps
    // 0.95 * 40000 = 38000.000000000004 from asking for 38001.
    const int64_t k = std::clamp<int64_t>(
        static_cast<int64_t>(std::ceil(rule.target_tpr * n - 1e-9)), 1, static_cast<int64_t>(n));
    int64_t seen = 0;
    size_t i = 0;
    for (; i < distances.size(); ++i) {
      if (distances[i].second && ++seen == k) break;
    }
    // Equal distances are accepted together; the threshold goes past the whole run.
    while (i + 1 < distances.size() && distances[i + 1].first == distances[i].first) ++i;
    model.threshold = ThresholdBetween(
        distances[i].first, i + 1 < distances.size() ? distances[i + 1].first : infinity);
  }

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
