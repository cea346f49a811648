#include "features/disparity_feature.h"

#include "config/read_fields.h"
#include "features/skin.h"
#include "stereo/disparity.h"

namespace attend {

namespace {

class DisparityFeature : public FeatureMap {
 public:
  DisparityFeature(const DisparityOptions& options, bool per_region)
      : options_(options), per_region_(per_region) {}

  bool NeedsStereo() const override { return true; }
  bool ReadsAttentionRegions() const override { return false; }

  // The context computes the disparity, once a frame, shared with plugins that ask for it.
  void Compute(const FrameContext& context, cv::Mat* out) override {
    context.Disparity(options_).convertTo(*out, CV_32F, 1.0 / (options_.max_disparity - 1));
    if (per_region_) AverageOverRegions(context.Regions(), out);
  }

 private:
  DisparityOptions options_;
  bool per_region_;
};

}  // namespace

const OptionFields<DisparityFeatureOptions>& DisparityFeatureOptions::Fields() {
  static const OptionFields<DisparityFeatureOptions> fields = {
      {"per_region", &DisparityFeatureOptions::per_region,
       "each BIP colour region takes the mean disparity of its pixels"}};
  return fields;
}

const std::vector<std::string>& DisparityOptionKeys() {
  static const std::vector<std::string> keys = FieldKeys(DisparityOptions::Fields());
  return keys;
}

DisparityOptions ReadDisparityOptions(const ParamBlock& block, DisparityOptions options) {
  ReadFields(block, DisparityOptions::Fields(), &options);
  const std::string error = options.Check();
  if (!error.empty()) block.FailCheck(error);
  return options;
}

std::unique_ptr<FeatureMap> CreateDisparityFeature(const ParamBlock& params, const FeatureSetup&) {
  DisparityFeatureOptions options;
  options.disparity = ReadDisparityOptions(params);
  // The map is divided by D - 1.
  if (options.disparity.max_disparity < 2) {
    params.Fail("max_disparity", "must be >= 2 for the feature");
  }
  ReadFields(params, DisparityFeatureOptions::Fields(), &options);
  return std::make_unique<DisparityFeature>(options.disparity, options.per_region);
}

}  // namespace attend
