#include "semiattentive/object_files.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "semiattentive/reidentification.h"

namespace attend {

const OptionFields<ObjectFileOptions>& ObjectFileOptions::Fields() {
  using O = ObjectFileOptions;
  static const OptionFields<ObjectFileOptions> fields = {
      {"memory_frames", &O::memory_frames, Range::Closed(0, 100000),
       "frames an object file is kept; 0: no object files"},
      {"memory_gate", &O::gate, Range::Closed(0, 100),
       "a new target's centre within this many box sides of the predicted centre"},
      {"memory_max_size_ratio", &O::max_size_ratio, Range::Closed(1, 100),
       "its box's sides within this factor of the remembered ones"},
      {"memory_min_similarity", &O::min_similarity, Range::Closed(0, 1),
       "its appearance at least this like the remembered one"},
      {"memory_velocity_decay", &O::velocity_decay, Range::Closed(0, 1),
       "the remembered velocity's factor each frame unseen"},
      {"dwell_s", &O::dwell_s, Range::Closed(0, 1e6),
       "a target found this many seconds is released into its object file; 0: held while "
       "salient (the thesis)"}};
  return fields;
}

std::string ObjectFileOptions::Check() const { return CheckFieldRanges(*this, Fields()); }

ObjectAppearance ObjectAppearance::Of(const cv::Mat& bgr, const cv::Mat& mask,
                                      const cv::Rect& box) {
  ObjectAppearance appearance;
  const cv::Rect area = box & cv::Rect(0, 0, bgr.cols, bgr.rows);
  if (area.empty()) return appearance;
  cv::Mat hsv;
  cv::cvtColor(bgr(area), hsv, cv::COLOR_BGR2HSV);
  const int channels[] = {0, 1, 2};
  const int bins[] = {kHueBins, kSaturationBins, kValueBins};
  const float hue[] = {0.f, 180.f}, saturation[] = {0.f, 256.f}, value[] = {0.f, 256.f};
  const float* ranges[] = {hue, saturation, value};
  const cv::Mat inside = mask.empty() ? cv::Mat() : mask(area);
  cv::calcHist(&hsv, 1, channels, inside, appearance.histogram, 3, bins, ranges);
  const double mass = cv::sum(appearance.histogram)[0];
  if (!(mass > 0.0)) return ObjectAppearance();
  appearance.histogram /= mass;

  cv::Mat grey, small;
  cv::cvtColor(bgr(area), grey, cv::COLOR_BGR2GRAY);
  cv::resize(grey, small, cv::Size(kTemplateWidth, kTemplateHeight), 0, 0, cv::INTER_AREA);
  small.convertTo(appearance.grey, CV_32F);
  appearance.grey -= cv::mean(appearance.grey)[0];
  const double norm = cv::norm(appearance.grey);
  appearance.contrast = static_cast<float>(norm / std::sqrt(appearance.grey.total()));
  if (norm > 1e-6) appearance.grey /= norm;
  return appearance;
}

void ObjectAppearance::Blend(const ObjectAppearance& seen, float rate) {
  if (seen.empty()) return;
  if (!seen.embedding.empty()) {
    if (embedding.empty() || embedding.total() != seen.embedding.total()) {
      embedding = seen.embedding.clone();
    } else {
      cv::addWeighted(embedding, 1.0 - rate, seen.embedding, rate, 0.0, embedding);
      const double norm = cv::norm(embedding);
      if (norm > 1e-12) embedding /= norm;
    }
  }
  if (empty()) {
    histogram = seen.histogram.clone();
    grey = seen.grey.clone();
    contrast = seen.contrast;
    return;
  }
  cv::addWeighted(histogram, 1.0 - rate, seen.histogram, rate, 0.0, histogram);
  cv::addWeighted(grey, 1.0 - rate, seen.grey, rate, 0.0, grey);
  contrast += rate * (seen.contrast - contrast);
}

double ObjectAppearance::Similarity(const ObjectAppearance& other) const {
  if (empty() || other.empty()) return 0.0;
  if (!embedding.empty() && !other.embedding.empty()) {
    return EmbeddingSimilarity(embedding, other.embedding);
  }
  const double colour =
      std::clamp(cv::compareHist(histogram, other.histogram, cv::HISTCMP_INTERSECT), 0.0, 1.0);
  if (contrast < kMinContrast || other.contrast < kMinContrast) return colour;
  const double norms = cv::norm(grey) * cv::norm(other.grey);
  const double shape = norms > 1e-9 ? std::max(0.0, grey.dot(other.grey) / norms) : 0.0;
  return 0.5 * (colour + shape);
}

cv::Rect ObjectFile::Predicted(float velocity_decay) const {
  // The distance covered while the speed decays geometrically: v (d + d^2 + ... + d^absent).
  double travel = absent;
  if (velocity_decay < 1.f) {
    travel = velocity_decay * (1.0 - std::pow(velocity_decay, absent)) / (1.0 - velocity_decay);
  }
  return cv::Rect(static_cast<int>(std::lround(box.x + velocity.x * travel)),
                  static_cast<int>(std::lround(box.y + velocity.y * travel)), box.width,
                  box.height);
}

void ObjectFiles::Age() {
  for (ObjectFile& file : files_) ++file.absent;
  files_.erase(std::remove_if(
                   files_.begin(), files_.end(),
                   [this](const ObjectFile& file) { return file.absent > options_.memory_frames; }),
               files_.end());
}

void ObjectFiles::Remember(ObjectFile file) {
  if (!enabled() || file.box.empty() || file.appearance.empty()) return;
  files_.push_back(std::move(file));
}

int ObjectFiles::Match(const cv::Rect& box, const ObjectAppearance& appearance, bool skin) const {
  int best = -1;
  double best_similarity = options_.min_similarity;
  const cv::Point2f centre(box.x + 0.5f * box.width, box.y + 0.5f * box.height);
  for (size_t i = 0; i < files_.size(); ++i) {
    const ObjectFile& file = files_[i];
    if (file.skin != skin) continue;
    const double width_ratio = static_cast<double>(box.width) / file.box.width;
    const double height_ratio = static_cast<double>(box.height) / file.box.height;
    const double size = options_.max_size_ratio;
    if (width_ratio > size || width_ratio < 1.0 / size || height_ratio > size ||
        height_ratio < 1.0 / size) {
      continue;
    }
    const cv::Rect predicted = file.Predicted(options_.velocity_decay);
    const cv::Point2f expected(predicted.x + 0.5f * predicted.width,
                               predicted.y + 0.5f * predicted.height);
    // The object may have walked on at its last speed while unseen, or turned back.
    const float speed = std::hypot(file.velocity.x, file.velocity.y);
    const float slack = speed * static_cast<float>(file.absent);
    if (std::abs(centre.x - expected.x) > options_.gate * file.box.width + slack ||
        std::abs(centre.y - expected.y) > options_.gate * file.box.height + slack) {
      continue;
    }
    const double similarity = appearance.Similarity(file.appearance);
    if (similarity >= best_similarity) best = static_cast<int>(i), best_similarity = similarity;
  }
  return best;
}

ObjectFile ObjectFiles::Take(int index) {
  ObjectFile file = std::move(files_[index]);
  files_.erase(files_.begin() + index);
  return file;
}

void ObjectFiles::Inhibit(cv::Mat* inhibition) const {
  const cv::Rect image(0, 0, inhibition->cols, inhibition->rows);
  for (const ObjectFile& file : files_) {
    const cv::Rect area = file.Predicted(options_.velocity_decay) & image;
    if (area.empty()) continue;
    const float strength =
        1.f - static_cast<float>(file.absent) / static_cast<float>(options_.memory_frames + 1);
    cv::Mat part = (*inhibition)(area);
    cv::max(part, cv::Scalar(strength), part);
  }
}

std::vector<cv::Rect> ObjectFiles::PredictedBoxes(const cv::Rect& image) const {
  std::vector<cv::Rect> boxes;
  for (const ObjectFile& file : files_) {
    const cv::Rect box = file.Predicted(options_.velocity_decay) & image;
    if (!box.empty()) boxes.push_back(box);
  }
  return boxes;
}

}  // namespace attend
