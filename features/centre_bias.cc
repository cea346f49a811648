#include "features/centre_bias.h"

#include <cmath>

#include "config/read_fields.h"

namespace attend {

namespace {

class CentreBiasFeature final : public FeatureMap {
 public:
  bool ReadsAttentionRegions() const override { return false; }
  explicit CentreBiasFeature(double sigma) : sigma_(sigma) {}
  void Compute(const FrameContext& context, cv::Mat* out) override {
    // The map depends on the size alone: made once per size.
    if (map_.size() != context.size()) CentreBiasMap(context.size(), sigma_, &map_);
    map_.copyTo(*out);
  }

 private:
  double sigma_;
  cv::Mat map_;
};

}  // namespace

const OptionFields<CentreBiasOptions>& CentreBiasOptions::Fields() {
  static const OptionFields<CentreBiasOptions> fields = {
      {"sigma", &CentreBiasOptions::sigma, Range::AboveUpTo(0, 10),
       "the Gaussian's sigma, share of the width (x) and height (y)"}};
  return fields;
}

void CentreBiasMap(cv::Size size, double sigma, cv::Mat* out) {
  CV_Assert(size.width > 0 && size.height > 0 && sigma > 0.0);
  out->create(size, CV_32FC1);
  const double cx = (size.width - 1) / 2.0, cy = (size.height - 1) / 2.0;
  const double sx = sigma * size.width, sy = sigma * size.height;
  std::vector<float> column(size.width);
  for (int x = 0; x < size.width; ++x) {
    const double d = (x - cx) / sx;
    column[x] = static_cast<float>(std::exp(-0.5 * d * d));
  }
  for (int y = 0; y < size.height; ++y) {
    const double d = (y - cy) / sy;
    const float row = static_cast<float>(std::exp(-0.5 * d * d));
    float* line = out->ptr<float>(y);
    for (int x = 0; x < size.width; ++x) line[x] = row * column[x];
  }
}

std::unique_ptr<FeatureMap> CreateCentreBiasFeature(const ParamBlock& params,
                                                    const FeatureSetup&) {
  CentreBiasOptions options;
  ReadFields(params, CentreBiasOptions::Fields(), &options);
  return std::make_unique<CentreBiasFeature>(options.sigma);
}

}  // namespace attend
