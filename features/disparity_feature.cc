#include "features/disparity_feature.h"

#include <algorithm>

#include "config/read_fields.h"
#include "features/lazy_frame_context.h"
#include "features/skin.h"
#include "stereo/depth_contrast.h"
#include "stereo/disparity.h"
#include "stereo/ground_plane.h"

namespace attend {

namespace {

class DisparityFeature : public FeatureMap {
 public:
  explicit DisparityFeature(const DisparityFeatureOptions& options)
      : options_(options.disparity),
        per_region_(options.per_region),
        contrast_(options.score == "contrast"),
        surround_(options.surround) {}

  bool NeedsStereo() const override { return true; }
  bool ReadsAttentionRegions() const override { return false; }

  // The context computes the disparity, once a frame, shared with plugins that ask for it.
  void Compute(const FrameContext& context, cv::Mat* out) override {
    const cv::Mat& disparity = context.Disparity(options_);
    if (contrast_) {
      *out = Contrast(context, disparity);
    } else {
      disparity.convertTo(*out, CV_32F, 1.0 / (options_.max_disparity - 1));
    }
    if (per_region_) AverageOverRegions(context.Regions(), out);
  }

 private:
  // score contrast: DepthContrast over the measured pixels, the surround's window `surround_`
  // of the width. The measured pixels are the frame context's (attend's own); a context of
  // another kind gives none, and every pixel counts as measured.
  cv::Mat Contrast(const FrameContext& context, const cv::Mat& disparity) const {
    const auto* lazy = dynamic_cast<const LazyFrameContext*>(&context);
    cv::Mat measured = lazy != nullptr ? lazy->DisparityMeasured(options_)
                                       : cv::Mat(disparity.size(), CV_8UC1, cv::Scalar(255));
    const GroundPlane ground =
        lazy != nullptr ? lazy->DisparityGround(options_) : FitGroundPlane(disparity, measured);
    const int window = std::max(3, static_cast<int>(surround_ * disparity.cols) | 1);
    cv::Mat contrast = DepthContrast(disparity, measured, ground, window);
    // Each colour region takes the mean over its measured pixels: a plain object is measured
    // at its edges only, and is as near as they are.
    AverageOverRegions(context.Regions(), &contrast, measured);
    return contrast;
  }

  DisparityOptions options_;
  bool per_region_;
  bool contrast_;
  float surround_;
};

const std::vector<std::string>& DisparityScores() {
  static const std::vector<std::string> scores = {"contrast", "nearness"};
  return scores;
}

}  // namespace

const OptionFields<DisparityFeatureOptions>& DisparityFeatureOptions::Fields() {
  static const OptionFields<DisparityFeatureOptions> fields = {
      {"per_region", &DisparityFeatureOptions::per_region,
       "each BIP colour region takes the mean disparity of its pixels"},
      {"score", &DisparityFeatureOptions::score,
       "contrast: nearer than the surround, off the ground; nearness: nearer is more salient (the "
       "thesis)",
       &DisparityScores},
      {"surround", &DisparityFeatureOptions::surround, Range::AboveUpTo(0, 1),
       "contrast: the side of the surround's window, a share of the width"}};
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
  return std::make_unique<DisparityFeature>(options);
}

}  // namespace attend
