#include "features/detection_map.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>

#include "util/box.h"

namespace attend {

void SuppressOverlaps(double max_iou, std::vector<Detection>* detections) {
  std::stable_sort(
      detections->begin(), detections->end(),
      [](const Detection& a, const Detection& b) { return a.confidence > b.confidence; });
  std::vector<Detection> kept;
  kept.reserve(detections->size());
  for (Detection& candidate : *detections) {
    bool overlaps = false;
    for (const Detection& other : kept) {
      if (other.label == candidate.label && BoxIou(other.box, candidate.box) > max_iou) {
        overlaps = true;
        break;
      }
    }
    if (!overlaps) kept.push_back(std::move(candidate));
  }
  *detections = std::move(kept);
}

namespace {

// A Gaussian over `box` (sigma `share` times its width and height, centred across it and at
// `centre_y` of its height from the top) up to `peak`, to 3 sigma, into `map` by the maximum.
void PaintGaussian(const cv::Rect& box, double share, double centre_y, float peak, cv::Mat* map) {
  const double sx = std::max(0.5, share * box.width);
  const double sy = std::max(0.5, share * box.height);
  const double cx = box.x + box.width / 2.0 - 0.5;
  const double cy = box.y + box.height * centre_y - 0.5;
  const cv::Rect reach = cv::Rect(cv::Point(static_cast<int>(std::floor(cx - 3 * sx)),
                                            static_cast<int>(std::floor(cy - 3 * sy))),
                                  cv::Point(static_cast<int>(std::ceil(cx + 3 * sx)) + 1,
                                            static_cast<int>(std::ceil(cy + 3 * sy)) + 1)) &
                         cv::Rect(0, 0, map->cols, map->rows);
  for (int y = reach.y; y < reach.y + reach.height; ++y) {
    float* row = map->ptr<float>(y);
    const double dy = (y - cy) / sy;
    for (int x = reach.x; x < reach.x + reach.width; ++x) {
      const double dx = (x - cx) / sx;
      const float value = peak * static_cast<float>(std::exp(-0.5 * (dx * dx + dy * dy)));
      row[x] = std::max(row[x], value);
    }
  }
}

}  // namespace

void PaintDetections(const std::vector<Detection>& detections, const DetectionPaint& options,
                     cv::Size size, cv::Mat* map) {
  map->create(size, CV_32FC1);
  map->setTo(0.f);
  const cv::Rect frame(0, 0, size.width, size.height);
  for (const Detection& detection : detections) {
    if (detection.box.empty()) continue;
    float value = detection.confidence;
    if (options.size_power != 0.0) {
      value *= static_cast<float>(
          std::pow(static_cast<double>(detection.box.height) / size.height, options.size_power));
    }
    if (options.shape == DetectionShape::kGaussian) {
      PaintGaussian(detection.box, options.sigma, options.centre_y, value, map);
      continue;
    }
    const cv::Rect box = detection.box & frame;
    if (box.empty()) continue;
    cv::Mat inside = (*map)(box);
    cv::max(inside, static_cast<double>(value), inside);
  }
  const double blur = options.blur;
  if (blur > 0.0 && !detections.empty()) {
    const double sigma = blur * std::max(size.width, size.height);
    cv::GaussianBlur(*map, *map, cv::Size(), sigma, sigma, cv::BORDER_CONSTANT);
  }
}

float ScoreToConfidence(double score) {
  // 1 / (1 + e^-s) rounds to 1 for large s in float, still in (0, 1]; it never reaches 0 for
  // the scores a detector keeps, but clamp the float so that no box paints a 0.
  const float confidence = static_cast<float>(1.0 / (1.0 + std::exp(-score)));
  return std::max(confidence, std::numeric_limits<float>::min());
}

}  // namespace attend
