// The disparity in the frame context (FrameContext::Disparity): computed once a frame for each
// options, equal to DisparityEstimator's, and the map the `disparity` feature uses.
#include <gtest/gtest.h>

#include <algorithm>
#include <opencv2/core.hpp>

#include "features/builtin.h"
#include "features/feature_set.h"
#include "features/lazy_frame_context.h"

namespace attend {
namespace {

// A random texture and the same texture moved `shift` pixels to the left: every left pixel
// (x, y) away from the left border matches the right pixel (x - shift, y), disparity `shift`.
struct Pair {
  cv::Mat left;
  cv::Mat right;
};
Pair ShiftedTexture(int shift) {
  cv::RNG rng(7);
  cv::Mat texture(48, 96 + shift, CV_8UC3);
  rng.fill(texture, cv::RNG::UNIFORM, 0, 256);
  return {texture(cv::Rect(0, 0, 96, 48)).clone(), texture(cv::Rect(shift, 0, 96, 48)).clone()};
}

double MedianInside(const cv::Mat& disparity) {
  const cv::Mat inside = disparity(cv::Rect(20, 8, 66, 32)).clone();
  std::vector<float> values(inside.begin<float>(), inside.end<float>());
  std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
  return values[values.size() / 2];
}

DisparityOptions WithWindow(int window) {
  DisparityOptions options;
  options.max_disparity = 16;
  options.window = window;
  return options;
}

TEST(FrameContext, ComputesTheDisparityOnceAFrameForEachOptions) {
  LazyFrameContext context;
  const Pair four = ShiftedTexture(4);
  context.Reset(0, four.left, four.right);
  const cv::Mat& seven = context.Disparity(WithWindow(7));
  EXPECT_EQ(&seven, &context.Disparity(WithWindow(7)));
  EXPECT_EQ(MedianInside(seven), 4.0);
  cv::Mat expected;
  DisparityEstimator(WithWindow(7)).Compute(four.left, four.right, &expected);
  EXPECT_EQ(cv::norm(seven, expected, cv::NORM_INF), 0.0);
  // Other options: a map of their own.
  const cv::Mat& nine = context.Disparity(WithWindow(9));
  EXPECT_NE(&seven, &nine);
  DisparityEstimator(WithWindow(9)).Compute(four.left, four.right, &expected);
  EXPECT_EQ(cv::norm(nine, expected, cv::NORM_INF), 0.0);
  // A new frame recomputes.
  const Pair six = ShiftedTexture(6);
  context.Reset(1, six.left, six.right);
  EXPECT_EQ(MedianInside(context.Disparity(WithWindow(7))), 6.0);
}

TEST(FrameContext, TheRunsDisparityOptionsAreTheDefaultsUntilSet) {
  LazyFrameContext context;
  EXPECT_TRUE(context.disparity_options() == DisparityOptions());
  context.set_disparity_options(WithWindow(9));
  EXPECT_EQ(context.disparity_options().window, 9);
}

TEST(FrameContext, TheDisparityFeatureUsesTheContextsMap) {
  const FeatureRegistry registry = BuiltinFeatures();
  FeatureSetup setup;
  setup.stereo = true;
  FeatureSet features(ReadFeatureList(ParamBlock::Parse("features: [{name: disparity, "
                                                        "max_disparity: 16, window: 9, "
                                                        "score: nearness}]",
                                                        "test.yaml"),
                                      "features"),
                      registry, setup);
  LazyFrameContext context;
  const Pair four = ShiftedTexture(4);
  context.Reset(0, four.left, four.right);
  // A plugin asks first, with the feature's options; the feature then reads that same map. To
  // tell a shared map from an equal one computed again, the shared one is overwritten here.
  cv::Mat& shared = const_cast<cv::Mat&>(context.Disparity(WithWindow(9)));
  shared.setTo(3.0f);
  features.Compute(context);
  const cv::Mat& map = features.results()[0].map;
  EXPECT_NEAR(cv::norm(map, cv::NORM_INF), 3.0 / 15.0, 1e-6);
  EXPECT_NEAR(cv::norm(map, cv::NORM_L1), 3.0 / 15.0 * map.total(), 1e-3);
}

}  // namespace
}  // namespace attend
