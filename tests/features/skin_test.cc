#include "features/skin.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "colour/colour.h"
#include "features/builtin.h"
#include "features/lazy_frame_context.h"
#include "synth/renderer.h"
#include "synth/scene.h"
#include "tests/support/temp_dir.h"

namespace attend {
namespace {

// Two colours in one image; the model is centred on the first.
struct TwoColours {
  cv::Mat bgr;
  cv::Mat tsl;
  SkinModel model;
};

TwoColours MakeTwoColours(cv::Vec3b centre, cv::Vec3b other) {
  TwoColours data;
  data.bgr.create(4, 4, CV_8UC3);
  data.bgr.setTo(centre);
  data.bgr(cv::Rect(2, 0, 2, 4)).setTo(other);
  BgrToTsl(data.bgr, &data.tsl);
  const cv::Vec2f mean = TslChrominance(centre[2], centre[1], centre[0]);
  data.model.mean = {mean[0], mean[1]};
  data.model.covariance << 0.02 * 0.02, 0.0, 0.0, 20.0 * 20.0;
  data.model.threshold = 4.0;
  return data;
}

TEST(Skin, MapFollowsTheMahalanobisDistance) {
  const cv::Vec3b skin(140, 172, 224), blue(200, 60, 20);
  TwoColours data = MakeTwoColours(skin, blue);
  cv::Mat binary, soft;
  SkinMap(data.tsl, data.model, SkinOutput::kBinary, &binary);
  SkinMap(data.tsl, data.model, SkinOutput::kSoft, &soft);
  EXPECT_EQ(binary.at<float>(1, 1), 1.f);
  EXPECT_EQ(binary.at<float>(1, 3), 0.f);
  EXPECT_NEAR(soft.at<float>(1, 1), 1.f, 1e-5);  // at the mean
  EXPECT_EQ(soft.at<float>(1, 3), 0.f);

  // A colour at a known distance: d^2 = (dt / 0.02)^2 + (ds / 20)^2.
  const cv::Vec3b near(150, 175, 222);
  TwoColours close = MakeTwoColours(skin, near);
  const cv::Vec2f a = TslChrominance(skin[2], skin[1], skin[0]);
  const cv::Vec2f b = TslChrominance(near[2], near[1], near[0]);
  const double d2 = std::pow((b[0] - a[0]) / 0.02, 2) + std::pow((b[1] - a[1]) / 20.0, 2);
  ASSERT_LT(d2, 4.0);
  ASSERT_GT(d2, 0.01);
  SkinMap(close.tsl, close.model, SkinOutput::kSoft, &soft);
  EXPECT_NEAR(soft.at<float>(0, 3), 1.0 - std::sqrt(d2 / 4.0), 1e-4);
  EXPECT_NEAR(close.model.SquaredDistance(b[0], b[1]), d2, 1e-6);
}

// The context computes a model's distance map once a frame and shares it: the second call
// returns the same pixels, a model with another mean gets its own map, and a new frame is
// computed anew. The skin feature and the attention stage both take it from there.
TEST(Skin, TheContextComputesEachModelsDistanceOnceAFrame) {
  cv::Mat first(8, 10, CV_8UC3, cv::Scalar(90, 120, 200));
  cv::Mat second(8, 10, CV_8UC3, cv::Scalar(200, 120, 90));
  SkinModel model;
  model.mean = Eigen::Vector2d(0.6, 40.0);
  model.covariance << 0.01, 0.0, 0.0, 100.0;
  SkinModel other = model;
  other.mean = Eigen::Vector2d(0.2, 10.0);

  LazyFrameContext context;
  context.Reset(0, first);
  const cv::Mat& distance = context.SkinDistance(model);
  cv::Mat expected;
  SkinDistanceMap(context.Tsl(), model, &expected);
  EXPECT_EQ(cv::norm(distance, expected, cv::NORM_INF), 0.0);
  EXPECT_EQ(context.SkinDistance(model).data, distance.data);  // shared, not recomputed
  const cv::Mat& other_distance = context.SkinDistance(other);
  EXPECT_NE(other_distance.data, distance.data);
  SkinDistanceMap(context.Tsl(), other, &expected);
  EXPECT_EQ(cv::norm(other_distance, expected, cv::NORM_INF), 0.0);

  context.Reset(1, second);
  SkinDistanceMap(context.Tsl(), model, &expected);
  EXPECT_EQ(cv::norm(context.SkinDistance(model), expected, cv::NORM_INF), 0.0);
}

TEST(Skin, PerRegionRemovesIsolatedPixels) {
  // A skin square, and three isolated skin pixels on a blue wall.
  cv::Mat image(40, 40, CV_8UC3, cv::Scalar(200, 60, 20));
  image(cv::Rect(20, 20, 12, 12)).setTo(cv::Scalar(140, 172, 224));
  for (const cv::Point p : {cv::Point(3, 3), cv::Point(10, 30), cv::Point(33, 5)}) {
    image.at<cv::Vec3b>(p) = cv::Vec3b(140, 172, 224);
  }
  const FeatureRegistry registry = BuiltinFeatures();
  FeatureSetup setup;
  setup.home = testing::ProjectRoot();
  LazyFrameContext context;
  context.Reset(0, image);
  cv::Mat pixels, regions;
  for (const bool per_region : {false, true}) {
    FeatureSpec spec;
    spec.name = "skin";
    spec.params = ParamBlock::Parse(per_region ? "per_region: true" : "{}", "test.yaml");
    registry.Create(spec, setup)->Compute(context, per_region ? &regions : &pixels);
  }
  EXPECT_EQ(pixels.at<float>(3, 3), 1.f);
  EXPECT_EQ(cv::countNonZero(pixels), 12 * 12 + 3);
  EXPECT_EQ(regions.at<float>(25, 25), 1.f);
  EXPECT_LT(regions.at<float>(3, 3), 0.01f);  // 3 pixels of the wall's 1453
}

TEST(Skin, FaceAndHandOfTheBundledSceneLightUp) {
  const std::string root = testing::ProjectRoot();
  const SceneRenderer renderer(LoadScene(root + "/sequences/lab.yaml"));
  const RenderedFrame frame = renderer.Render(10);

  const FeatureRegistry registry = BuiltinFeatures();
  FeatureSpec spec;
  spec.name = "skin";
  FeatureSetup setup;
  setup.home = root;
  std::unique_ptr<FeatureMap> feature = registry.Create(spec, setup);
  LazyFrameContext context;
  context.Reset(10, frame.left, frame.right);
  cv::Mat map;
  feature->Compute(context, &map);

  // Mean of the map over each object's pixels (ids 7 and 8 are the face and the hand).
  auto mean_over = [&](const cv::Mat& mask) { return cv::mean(map, mask)[0]; };
  const cv::Mat skin_pixels = (frame.left_ids == 7) | (frame.left_ids == 8);
  ASSERT_GT(cv::countNonZero(skin_pixels), 500);
  EXPECT_GT(mean_over(skin_pixels), 0.8);
  EXPECT_LT(mean_over(~skin_pixels), 0.05);
}

}  // namespace
}  // namespace attend
