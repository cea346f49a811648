#include "app/region_disparity.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "pyramid/segmentation.h"

namespace attend {

namespace {

cv::Mat Bgr(const cv::Mat& image) {
  if (image.channels() == 3) return image;
  cv::Mat bgr;
  cv::cvtColor(image, bgr, cv::COLOR_GRAY2BGR);
  return bgr;
}

// The median of the known (> 0, finite) values of `truth` under `mask`; NaN when none.
double KnownMedian(const cv::Mat& truth, const cv::Mat& mask) {
  std::vector<float> values;
  for (int y = 0; y < truth.rows; ++y) {
    const float* t = truth.ptr<float>(y);
    const uint8_t* m = mask.ptr<uint8_t>(y);
    for (int x = 0; x < truth.cols; ++x) {
      if (m[x] != 0 && t[x] > 0.f && std::isfinite(t[x])) values.push_back(t[x]);
    }
  }
  if (values.empty()) return std::nan("");
  const size_t middle = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + middle, values.end());
  return values[middle];
}

struct MethodErrors {
  std::vector<double> errors;
  nlohmann::json Summary() const {
    if (errors.empty()) return nullptr;
    std::vector<double> sorted = errors;
    std::sort(sorted.begin(), sorted.end());
    double sum = 0.0;
    int within = 0;
    for (const double e : sorted) {
      sum += e;
      within += e <= 1.0;
    }
    return {{"within_1px", static_cast<double>(within) / sorted.size()},
            {"median_abs_error_px", sorted[sorted.size() / 2]},
            {"mean_abs_error_px", sum / sorted.size()}};
  }
};

}  // namespace

nlohmann::json ScoreRegionDisparities(const cv::Mat& left, const cv::Mat& right,
                                      const cv::Mat& disparity, const cv::Mat& truth,
                                      const DisparityOptions& options, double min_fraction) {
  const cv::Mat left_bgr = Bgr(left), right_bgr = Bgr(right);
  Segmenter segmenter;
  Segmentation segmentation;
  segmenter.Segment(left_bgr, &segmentation);
  const double min_area = min_fraction * left.total();
  DepthOptions depth;
  MethodErrors template_errors, map_errors;
  nlohmann::json per_region = nlohmann::json::array();
  int skipped = 0;
  for (size_t r = 0; r < segmentation.regions.size(); ++r) {
    const cv::Mat mask = segmentation.labels == static_cast<int>(r);
    const int area = cv::countNonZero(mask);
    if (area < min_area) continue;
    const double expected = KnownMedian(truth, mask);
    if (!std::isfinite(expected)) {
      ++skipped;
      continue;
    }
    const cv::Rect box = cv::boundingRect(mask);
    const DisparityEstimate by_template = TemplateDisparity(
        left_bgr, right_bgr, mask, box, options.max_disparity, depth, options.window);
    const DisparityEstimate by_map = MapDisparity(disparity, mask, box, depth, options.window);
    nlohmann::json row = {{"region", r}, {"area", area}, {"box", {box.x, box.y, box.width, box.height}},
                          {"truth_px", expected}};
    const auto add = [&](const char* name, const DisparityEstimate& e, MethodErrors* errors) {
      if (!e.valid()) {
        row[name] = nullptr;
        errors->errors.push_back(std::abs(expected));  // no estimate: as wrong as 0
        return;
      }
      row[name] = {{"disparity_px", e.disparity}, {"sd_px", e.sd}};
      errors->errors.push_back(std::abs(e.disparity - expected));
    };
    add("template", by_template, &template_errors);
    add("map", by_map, &map_errors);
    per_region.push_back(row);
  }
  return {{"min_fraction", min_fraction},
          {"regions", per_region.size()},
          {"skipped_unknown", skipped},
          {"template", template_errors.Summary()},
          {"map", map_errors.Summary()},
          {"per_region", per_region}};
}

}  // namespace attend
