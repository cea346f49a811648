#include "features/disparity_feature.h"

#include "features/skin.h"
#include "stereo/disparity.h"

namespace attend {

namespace {

class DisparityFeature : public FeatureMap {
 public:
  DisparityFeature(const DisparityOptions& options, bool per_region)
      : estimator_(options), per_region_(per_region) {}

  bool NeedsStereo() const override { return true; }

  void Compute(const FrameContext& context, cv::Mat* out) override {
    estimator_.Compute(context.left(), context.right(), &disparity_);
    disparity_.convertTo(*out, CV_32F, 1.0 / (estimator_.options().max_disparity - 1));
    if (per_region_) AverageOverRegions(context.Regions(), out);
  }

 private:
  DisparityEstimator estimator_;
  bool per_region_;
  cv::Mat disparity_;
};

}  // namespace

std::unique_ptr<FeatureMap> CreateDisparityFeature(const ParamBlock& params, const FeatureSetup&) {
  DisparityOptions options;
  options.max_disparity =
      params.GetInt("max_disparity", options.max_disparity, Range::Closed(2, 1024));
  options.window = params.GetInt("window", options.window, Range::Closed(1, 31));
  if (options.window % 2 == 0) params.Fail("window", "must be odd");
  options.subpixel = params.GetBool("subpixel", options.subpixel);
  options.left_right_check = params.GetBool("left_right_check", options.left_right_check);
  options.lr_tolerance =
      params.GetInt("lr_tolerance", options.lr_tolerance, Range::Closed(0, 1024));
  options.smoothness = params.GetChoice("smoothness", options.smoothness, {"hard", "penalty"});
  options.jump_penalty =
      static_cast<float>(params.GetDouble("jump_penalty", options.jump_penalty, Range::AtLeast(0)));
  const bool per_region = params.GetBool("per_region", false);
  return std::make_unique<DisparityFeature>(options, per_region);
}

}  // namespace attend
