#include "features/skin.h"

#include <Eigen/LU>
#include <cmath>
#include <cstdio>
#include <opencv2/imgproc.hpp>

#include "config/read_fields.h"
#include "io/skin_files.h"
#include "util/enum_table.h"

namespace attend {

namespace {

class SkinFeature : public FeatureMap {
 public:
  bool ReadsAttentionRegions() const override { return false; }
  SkinFeature(SkinModel model, SkinOutput output, bool per_region)
      : model_(std::move(model)), output_(output), per_region_(per_region) {}
  void Compute(const FrameContext& context, cv::Mat* out) override {
    SkinMapFromDistance(context.SkinDistance(model_), model_, output_, out);
    if (per_region_) AverageOverRegions(context.Regions(), out);
  }

 private:
  SkinModel model_;
  SkinOutput output_;
  bool per_region_;
};

}  // namespace

void SkinMap(const cv::Mat& tsl, const SkinModel& model, SkinOutput output, cv::Mat* out) {
  // d^2 per pixel (SkinDistanceMap), then the binary or soft map of it, in place.
  SkinDistanceMap(tsl, model, out);
  SkinMapFromDistance(*out, model, output, out);
}

void SkinMapFromDistance(const cv::Mat& distance, const SkinModel& model, SkinOutput output,
                         cv::Mat* out) {
  CV_Assert(distance.type() == CV_32FC1);
  if (out->data != distance.data) out->create(distance.size(), CV_32FC1);
  const float threshold = static_cast<float>(model.threshold);
  const float inverse_threshold = 1.f / threshold;
  for (int y = 0; y < out->rows; ++y) {
    const float* squared = distance.ptr<float>(y);
    float* value = out->ptr<float>(y);
    for (int x = 0; x < out->cols; ++x) {
      const float d2 = squared[x];
      if (output == SkinOutput::kBinary) {
        value[x] = d2 < threshold ? 1.f : 0.f;
      } else {
        value[x] = std::max(0.f, 1.f - std::sqrt(d2 * inverse_threshold));
      }
    }
  }
}

namespace {

// d^2 = a dt^2 + 2 b dt ds + c ds^2 with [a b; b c] the inverse covariance; SkinMap thresholds
// it, so d^2 < T_s is exactly SkinMap's skin.
struct SkinMahalanobis {
  explicit SkinMahalanobis(const SkinModel& model) {
    const Eigen::Matrix2d inverse = model.covariance.inverse();
    a = static_cast<float>(inverse(0, 0));
    b2 = static_cast<float>(inverse(0, 1) + inverse(1, 0));
    c = static_cast<float>(inverse(1, 1));
    mean_t = static_cast<float>(model.mean.x());
    mean_s = static_cast<float>(model.mean.y());
  }
  float operator()(float t, float s) const {
    const float dt = t - mean_t;
    const float ds = s - mean_s;
    return a * dt * dt + b2 * dt * ds + c * ds * ds;
  }
  float a, b2, c, mean_t, mean_s;
};

}  // namespace

void SkinDistanceMap(const cv::Mat& tsl, const SkinModel& model, cv::Mat* out) {
  CV_Assert(tsl.type() == CV_32FC3);
  out->create(tsl.size(), CV_32FC1);
  const SkinMahalanobis distance(model);
  for (int y = 0; y < tsl.rows; ++y) {
    const float* pixel = tsl.ptr<float>(y);
    float* value = out->ptr<float>(y);
    for (int x = 0; x < tsl.cols; ++x) value[x] = distance(pixel[3 * x], pixel[3 * x + 1]);
  }
}

void SkinDistanceMapOfBgr(const cv::Mat& bgr, const SkinModel& model, cv::Mat* out) {
  out->create(bgr.size(), CV_32FC1);
  const SkinMahalanobis distance(model);
  ForEachTslRow(bgr, [&](int y, const float* t, const float* s, const float*) {
    float* value = out->ptr<float>(y);
    for (int x = 0; x < bgr.cols; ++x) value[x] = distance(t[x], s[x]);
  });
}

namespace {

constexpr EnumTable<SkinOutput, 2> kSkinOutputs = {
    {{{SkinOutput::kBinary, "binary"}, {SkinOutput::kSoft, "soft"}}}};

}  // namespace

const OptionFields<SkinFeatureOptions>& SkinFeatureOptions::Fields() {
  using O = SkinFeatureOptions;
  static const OptionFields<SkinFeatureOptions> fields = {
      {"output", EnumField<&O::output, kSkinOutputs>(),
       "binary: 1 where d^2 < T_s (the thesis); soft: max(0, 1 - sqrt(d^2 / T_s))"},
      {"model", &O::model, "the skin model file (attend skin-train makes one)"},
      {"per_region", &O::per_region, "each BIP colour region takes the mean of its pixels"}};
  return fields;
}

const OptionFields<SkinRegionOptions>& SkinRegionOptions::Fields() {
  using O = SkinRegionOptions;
  static const OptionFields<SkinRegionOptions> fields = {
      {"confident", &O::confident, Range::Closed(0.001, 1),
       "a pixel is confident skin when d^2 < this x T_s"},
      {"min_confident_share", &O::min_confident_share, Range::Closed(0, 1),
       "share of the region's pixels that are confident skin"},
      {"max_mean_distance", &O::max_mean_distance, Range::Closed(0, 1),
       "the region's mean of min(1, sqrt(d^2 / T_s)) at most this"},
      {"min_solidity", &O::min_solidity, Range::Closed(0, 1),
       "area over the convex hull's area at least this"},
      {"max_aspect_ratio", &O::max_aspect_ratio, Range::Closed(1, 1000),
       "long over short side of the minimum-area rectangle at most this"},
      {"max_area_fraction", &O::max_area_fraction, Range::AboveUpTo(0, 1),
       "share of the image at most this"},
      {"min_area", &O::min_area, Range::Closed(1, 1e8), "area at least this, px"}};
  return fields;
}

std::string SkinRegionOptions::Check() const { return CheckFieldRanges(*this, Fields(), ": "); }

std::string SkinRegionVerdict::Describe() const {
  char line[256];
  std::snprintf(line, sizeof(line),
                "%s: area %d (%.4f of the image), confident %.3f, mean distance %.3f, "
                "solidity %.3f, aspect %.2f%s%s",
                skin ? "skin" : "not skin", area, area_fraction, confident_share, mean_distance,
                solidity, aspect_ratio, failed.empty() ? "" : "; failed ", failed.c_str());
  return line;
}

SkinRegionVerdict JudgeSkinRegion(const cv::Mat& mask, const cv::Mat& distances, double threshold,
                                  const SkinRegionOptions& options) {
  CV_Assert(mask.type() == CV_8UC1 && distances.type() == CV_32FC1 &&
            mask.size() == distances.size() && threshold > 0.0);
  CV_Assert(options.Check().empty());
  SkinRegionVerdict verdict;
  const float confident_bound = static_cast<float>(options.confident * threshold);
  const double inverse_threshold = 1.0 / threshold;
  int64_t area = 0, confident = 0;
  double distance_sum = 0.0;
  cv::Rect box;  // of the region, to bound the shape measurements
  int min_x = mask.cols, min_y = mask.rows, max_x = -1, max_y = -1;
  for (int y = 0; y < mask.rows; ++y) {
    const uchar* inside = mask.ptr<uchar>(y);
    const float* d2 = distances.ptr<float>(y);
    for (int x = 0; x < mask.cols; ++x) {
      if (!inside[x]) continue;
      ++area;
      if (d2[x] < confident_bound) ++confident;
      distance_sum += std::min(1.0, std::sqrt(std::max(0.f, d2[x]) * inverse_threshold));
      min_x = std::min(min_x, x), max_x = std::max(max_x, x);
      min_y = std::min(min_y, y), max_y = std::max(max_y, y);
    }
  }
  verdict.area = static_cast<int>(area);
  verdict.area_fraction = static_cast<double>(area) / mask.total();
  if (area == 0) {
    verdict.failed = "min_area";
    return verdict;
  }
  box = cv::Rect(min_x, min_y, max_x - min_x + 1, max_y - min_y + 1);
  verdict.confident_share = static_cast<double>(confident) / area;
  verdict.mean_distance = distance_sum / area;

  // Shape, from the region's outer contours (all pieces together: a hand cut in two by a
  // shadow is judged as one). Holes count as region for the hull, not for the area.
  std::vector<std::vector<cv::Point>> contours;
  cv::findContours(mask(box).clone(), contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_SIMPLE);
  std::vector<cv::Point> points;
  for (const auto& contour : contours) points.insert(points.end(), contour.begin(), contour.end());
  std::vector<cv::Point> hull;
  cv::convexHull(points, hull);
  // The hull of pixel centres misses half a pixel all round; count the hull's own pixels.
  cv::Mat hull_mask = cv::Mat::zeros(box.size(), CV_8UC1);
  cv::fillConvexPoly(hull_mask, hull, cv::Scalar(255));
  const int hull_area = std::max(1, cv::countNonZero(hull_mask | (mask(box) != 0)));
  verdict.solidity = static_cast<double>(area) / hull_area;
  const cv::RotatedRect rectangle = cv::minAreaRect(points);
  const double long_side = std::max(rectangle.size.width, rectangle.size.height) + 1.0;
  const double short_side = std::min(rectangle.size.width, rectangle.size.height) + 1.0;
  verdict.aspect_ratio = long_side / short_side;

  // The tests, cheapest reason first in the order a reader checks them.
  if (area < options.min_area) {
    verdict.failed = "min_area";
  } else if (verdict.area_fraction > options.max_area_fraction) {
    verdict.failed = "max_area_fraction";
  } else if (verdict.confident_share < options.min_confident_share) {
    verdict.failed = "min_confident_share";
  } else if (verdict.mean_distance > options.max_mean_distance) {
    verdict.failed = "max_mean_distance";
  } else if (verdict.solidity < options.min_solidity) {
    verdict.failed = "min_solidity";
  } else if (verdict.aspect_ratio > options.max_aspect_ratio) {
    verdict.failed = "max_aspect_ratio";
  }
  verdict.skin = verdict.failed.empty();
  return verdict;
}

SkinRegionVerdict JudgeSkinRegionTsl(const cv::Mat& mask, const cv::Mat& tsl,
                                     const SkinModel& model, const SkinRegionOptions& options) {
  cv::Mat distances;
  SkinDistanceMap(tsl, model, &distances);
  return JudgeSkinRegion(mask, distances, model.threshold, options);
}

void AverageOverRegions(const Segmentation& segmentation, cv::Mat* map, const cv::Mat& over) {
  const cv::Mat& labels = segmentation.labels;
  CV_Assert(map->type() == CV_32FC1 && map->size() == labels.size());
  CV_Assert(over.empty() || (over.type() == CV_8UC1 && over.size() == labels.size()));
  std::vector<double> sums(segmentation.regions.size(), 0.0);
  std::vector<int> counts(segmentation.regions.size(), 0);
  for (int y = 0; y < labels.rows; ++y) {
    const int* label = labels.ptr<int>(y);
    const float* value = map->ptr<float>(y);
    const uint8_t* counted = over.empty() ? nullptr : over.ptr<uint8_t>(y);
    for (int x = 0; x < labels.cols; ++x) {
      if (label[x] < 0 || (counted != nullptr && counted[x] == 0)) continue;
      sums[label[x]] += value[x];
      ++counts[label[x]];
    }
  }
  std::vector<float> means(sums.size());
  for (size_t i = 0; i < sums.size(); ++i) {
    const int pixels = over.empty() ? segmentation.regions[i].area : counts[i];
    means[i] = static_cast<float>(sums[i] / std::max(1, pixels));
  }
  for (int y = 0; y < labels.rows; ++y) {
    const int* label = labels.ptr<int>(y);
    float* value = map->ptr<float>(y);
    for (int x = 0; x < labels.cols; ++x) value[x] = label[x] >= 0 ? means[label[x]] : 0.f;
  }
}

std::unique_ptr<FeatureMap> CreateSkinFeature(const ParamBlock& params, const FeatureSetup& setup) {
  SkinFeatureOptions options;
  ReadFields(params, SkinFeatureOptions::Fields(), &options);
  const std::string path = setup.ResolvePath(params, "model", options.model);
  return std::make_unique<SkinFeature>(LoadSkinModel(path), options.output, options.per_region);
}

}  // namespace attend
