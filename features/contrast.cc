#include "features/contrast.h"

#include <cmath>

namespace attend {

namespace {

// sum_j pl_ij g(i, j) / PL_i over the region adjacency graph, for a symmetric gradient g.
template <typename Gradient>
std::vector<float> MeanBoundaryGradient(const Segmentation& segmentation, Gradient gradient) {
  const std::vector<RegionStats>& regions = segmentation.regions;
  std::vector<double> sums(regions.size(), 0.0);
  for (const RegionBoundary& boundary : segmentation.adjacency.boundaries) {
    const int a = boundary.a, b = boundary.b;
    const double weighted = static_cast<double>(boundary.length) * gradient(regions[a], regions[b]);
    sums[a] += weighted;
    sums[b] += weighted;
  }
  std::vector<float> values(regions.size(), 0.f);
  for (size_t i = 0; i < regions.size(); ++i) {
    if (regions[i].perimeter > 0) values[i] = static_cast<float>(sums[i] / regions[i].perimeter);
  }
  return values;
}

class RegionFeature : public FeatureMap {
 public:
  bool ReadsAttentionRegions() const override { return false; }
  explicit RegionFeature(std::vector<float> (*measure)(const Segmentation&)) : measure_(measure) {}
  void Compute(const FrameContext& context, cv::Mat* out) override {
    const Segmentation& segmentation = context.Regions();
    PaintRegions(segmentation.labels, measure_(segmentation), out);
  }

 private:
  std::vector<float> (*measure_)(const Segmentation&);
};

}  // namespace

std::vector<float> ColourContrast(const Segmentation& segmentation) {
  std::vector<float> values =
      MeanBoundaryGradient(segmentation, [](const RegionStats& a, const RegionStats& b) {
        return CylinderDistance(a.colour, b.colour);
      });
  // S_i is a factor of the region, outside the sum.
  for (size_t i = 0; i < values.size(); ++i) {
    values[i] *= segmentation.regions[i].saturation / 255.f;
  }
  return values;
}

std::vector<float> IntensityContrast(const Segmentation& segmentation) {
  return MeanBoundaryGradient(segmentation, [](const RegionStats& a, const RegionStats& b) {
    return std::abs(a.intensity - b.intensity);
  });
}

void PaintRegions(const cv::Mat& labels, const std::vector<float>& values, cv::Mat* out) {
  CV_Assert(labels.type() == CV_32SC1);
  out->create(labels.size(), CV_32FC1);
  const int count = static_cast<int>(values.size());
  for (int y = 0; y < labels.rows; ++y) {
    const int* label = labels.ptr<int>(y);
    float* value = out->ptr<float>(y);
    for (int x = 0; x < labels.cols; ++x) {
      value[x] = label[x] >= 0 && label[x] < count ? values[label[x]] : 0.f;
    }
  }
}

std::unique_ptr<FeatureMap> CreateColourContrast(const ParamBlock&, const FeatureSetup&) {
  return std::make_unique<RegionFeature>(&ColourContrast);
}

std::unique_ptr<FeatureMap> CreateIntensityContrast(const ParamBlock&, const FeatureSetup&) {
  return std::make_unique<RegionFeature>(&IntensityContrast);
}

}  // namespace attend
