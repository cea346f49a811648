#include "features/contrast.h"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "features/builtin.h"
#include "features/lazy_frame_context.h"

namespace attend {
namespace {

// Computes one built-in feature on `image` with default parameters.
cv::Mat FeatureOf(const std::string& name, const cv::Mat& image) {
  const FeatureRegistry registry = BuiltinFeatures();
  FeatureSpec spec;
  spec.name = name;
  std::unique_ptr<FeatureMap> feature = registry.Create(spec, FeatureSetup{});
  LazyFrameContext context;
  context.Reset(0, image);
  cv::Mat map;
  feature->Compute(context, &map);
  EXPECT_EQ(map.type(), CV_32FC1);
  EXPECT_EQ(map.size(), image.size());
  return map;
}

cv::Mat SquareOn(cv::Scalar background, cv::Scalar square) {
  cv::Mat image(40, 60, CV_8UC3, background);
  image(cv::Rect(20, 10, 16, 16)).setTo(square);
  return image;
}

TEST(Contrast, SaturatedSquareBeatsGreySquareOfEqualIntensityContrast) {
  const cv::Scalar grey(100, 100, 100);
  const cv::Mat red = SquareOn(grey, cv::Scalar(0, 0, 255));        // V = 255, S = 255
  const cv::Mat white = SquareOn(grey, cv::Scalar(255, 255, 255));  // V = 255, S = 0
  const cv::Point inside(25, 15);
  // Equal intensity contrast: |255 - 100| along the whole boundary, for both squares.
  EXPECT_NEAR(FeatureOf("intensity_contrast", red).at<float>(inside), 155.f, 1e-3);
  EXPECT_NEAR(FeatureOf("intensity_contrast", white).at<float>(inside), 155.f, 1e-3);
  // Colour contrast: the red square's saturation is 1 and its colour distance to grey is
  // |(255, 0, 255) - (0, 0, 100)| = sqrt(255^2 + 155^2); the white square's saturation is 0.
  const float red_mcg = FeatureOf("colour_contrast", red).at<float>(inside);
  EXPECT_NEAR(red_mcg, std::sqrt(255.f * 255.f + 155.f * 155.f), 1e-2);
  EXPECT_EQ(FeatureOf("colour_contrast", white).at<float>(inside), 0.f);
  EXPECT_GT(red_mcg, 0.f);
}

TEST(Contrast, ThreeRegionsMatchEquationByHand) {
  // Left half red; right half blue above grey. Boundaries: red-blue 10 pixel edges, red-grey
  // 10, blue-grey 15 (the image border does not count).
  cv::Mat image(20, 30, CV_8UC3, cv::Scalar(0, 0, 255));
  image(cv::Rect(15, 0, 15, 10)).setTo(cv::Scalar(255, 0, 0));
  image(cv::Rect(15, 10, 15, 10)).setTo(cv::Scalar(128, 128, 128));
  const cv::Mat mcg = FeatureOf("colour_contrast", image);
  const cv::Mat mig = FeatureOf("intensity_contrast", image);

  // Cylinder colours (S cos H, S sin H, V): red (255, 0, 255), blue at H = 240 degrees
  // (-127.5, -220.836, 255), grey (0, 0, 128).
  const double s3 = 255.0 * std::sqrt(3.0) / 2.0;
  const double red_blue = std::hypot(255.0 + 127.5, s3);
  const double red_grey = std::hypot(255.0, 127.0);
  const double blue_grey = std::sqrt(127.5 * 127.5 + s3 * s3 + 127.0 * 127.0);
  EXPECT_NEAR(mcg.at<float>(5, 5), (10 * red_blue + 10 * red_grey) / 20, 1e-2);
  EXPECT_NEAR(mcg.at<float>(5, 20), (10 * red_blue + 15 * blue_grey) / 25, 1e-2);
  EXPECT_EQ(mcg.at<float>(15, 20), 0.f);  // grey: saturation 0
  // Intensities 255, 255, 128.
  EXPECT_NEAR(mig.at<float>(5, 5), (10 * 0 + 10 * 127) / 20.0, 1e-3);
  EXPECT_NEAR(mig.at<float>(5, 20), (10 * 0 + 15 * 127) / 25.0, 1e-3);
  EXPECT_NEAR(mig.at<float>(15, 20), (10 * 127 + 15 * 127) / 25.0, 1e-3);
}

TEST(Contrast, RegionWithoutNeighboursScoresZero) {
  const cv::Mat flat(30, 30, CV_8UC3, cv::Scalar(0, 0, 255));
  EXPECT_EQ(cv::countNonZero(FeatureOf("colour_contrast", flat)), 0);
  EXPECT_EQ(cv::countNonZero(FeatureOf("intensity_contrast", flat)), 0);
}

TEST(Contrast, WhiteSquareOnBlackScoresItsAnalyticValue) {
  const cv::Mat image = SquareOn(cv::Scalar(0, 0, 0), cv::Scalar(255, 255, 255));
  const cv::Mat mig = FeatureOf("intensity_contrast", image);
  // Every boundary edge of either region separates 255 from 0.
  EXPECT_NEAR(mig.at<float>(15, 25), 255.f, 1e-3);
  EXPECT_NEAR(mig.at<float>(2, 2), 255.f, 1e-3);
}

TEST(Contrast, PaintRegionsLeavesOutsideTheMaskAtZero) {
  cv::Mat labels = (cv::Mat_<int>(2, 3) << 0, 1, -1, 1, 0, -1);
  cv::Mat out;
  PaintRegions(labels, {2.f, 5.f}, &out);
  EXPECT_EQ(out.at<float>(0, 0), 2.f);
  EXPECT_EQ(out.at<float>(0, 1), 5.f);
  EXPECT_EQ(out.at<float>(0, 2), 0.f);
  EXPECT_EQ(out.at<float>(1, 0), 5.f);
}

}  // namespace
}  // namespace attend
