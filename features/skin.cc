#include "features/skin.h"

#include <Eigen/LU>
#include <cmath>

namespace attend {

namespace {

class SkinFeature : public FeatureMap {
 public:
  SkinFeature(SkinModel model, SkinOutput output, bool per_region)
      : model_(std::move(model)), output_(output), per_region_(per_region) {}
  void Compute(const FrameContext& context, cv::Mat* out) override {
    SkinMap(context.Tsl(), model_, output_, out);
    if (per_region_) AverageOverRegions(context.Regions(), out);
  }

 private:
  SkinModel model_;
  SkinOutput output_;
  bool per_region_;
};

}  // namespace

void SkinMap(const cv::Mat& tsl, const SkinModel& model, SkinOutput output, cv::Mat* out) {
  CV_Assert(tsl.type() == CV_32FC3);
  out->create(tsl.size(), CV_32FC1);
  // d^2 = a dt^2 + 2 b dt ds + c ds^2 with [a b; b c] the inverse covariance.
  const Eigen::Matrix2d inverse = model.covariance.inverse();
  const float a = static_cast<float>(inverse(0, 0));
  const float b2 = static_cast<float>(inverse(0, 1) + inverse(1, 0));
  const float c = static_cast<float>(inverse(1, 1));
  const float mean_t = static_cast<float>(model.mean.x());
  const float mean_s = static_cast<float>(model.mean.y());
  const float threshold = static_cast<float>(model.threshold);
  const float inverse_threshold = 1.f / threshold;
  for (int y = 0; y < tsl.rows; ++y) {
    const float* pixel = tsl.ptr<float>(y);
    float* value = out->ptr<float>(y);
    for (int x = 0; x < tsl.cols; ++x) {
      const float dt = pixel[3 * x] - mean_t;
      const float ds = pixel[3 * x + 1] - mean_s;
      const float d2 = a * dt * dt + b2 * dt * ds + c * ds * ds;
      if (output == SkinOutput::kBinary) {
        value[x] = d2 < threshold ? 1.f : 0.f;
      } else {
        value[x] = std::max(0.f, 1.f - std::sqrt(d2 * inverse_threshold));
      }
    }
  }
}

void AverageOverRegions(const Segmentation& segmentation, cv::Mat* map) {
  const cv::Mat& labels = segmentation.labels;
  CV_Assert(map->type() == CV_32FC1 && map->size() == labels.size());
  std::vector<double> sums(segmentation.regions.size(), 0.0);
  for (int y = 0; y < labels.rows; ++y) {
    const int* label = labels.ptr<int>(y);
    const float* value = map->ptr<float>(y);
    for (int x = 0; x < labels.cols; ++x) {
      if (label[x] >= 0) sums[label[x]] += value[x];
    }
  }
  std::vector<float> means(sums.size());
  for (size_t i = 0; i < sums.size(); ++i) {
    means[i] = static_cast<float>(sums[i] / std::max(1, segmentation.regions[i].area));
  }
  for (int y = 0; y < labels.rows; ++y) {
    const int* label = labels.ptr<int>(y);
    float* value = map->ptr<float>(y);
    for (int x = 0; x < labels.cols; ++x) value[x] = label[x] >= 0 ? means[label[x]] : 0.f;
  }
}

std::unique_ptr<FeatureMap> CreateSkinFeature(const ParamBlock& params, const FeatureSetup& setup) {
  const std::string output = params.GetChoice("output", "binary", {"binary", "soft"});
  const std::string path =
      setup.ResolvePath(params, "model", params.GetString("model", "configs/skin_tsl.yaml"));
  const bool per_region = params.GetBool("per_region", false);
  return std::make_unique<SkinFeature>(
      LoadSkinModel(path), output == "soft" ? SkinOutput::kSoft : SkinOutput::kBinary, per_region);
}

}  // namespace attend
