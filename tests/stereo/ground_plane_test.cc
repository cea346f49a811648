// The ground plane (stereo/ground_plane.h) and depth contrast (stereo/depth_contrast.h) on
// disparity maps drawn with a known ground: a level camera sees a flat ground whose disparity
// grows linearly below the horizon, d = slope (v - horizon), and upright objects standing on it
// hold the ground's disparity at their base row on all their rows.
#include "stereo/ground_plane.h"

#include <gtest/gtest.h>

#include "stereo/depth_contrast.h"

namespace attend {
namespace {

constexpr int kWidth = 160, kHeight = 120;
constexpr double kSlope = 0.25, kHorizon = 40.0;

// The drawn scene: the sky above the horizon (not measured), the ground below, and an upright
// object on columns 60..89 standing on row 95 (rows 50..95).
struct Street {
  cv::Mat disparity = cv::Mat::zeros(kHeight, kWidth, CV_32FC1);
  cv::Mat measured = cv::Mat::zeros(kHeight, kWidth, CV_8UC1);
  cv::Rect object{60, 50, 30, 46};
  float object_disparity = static_cast<float>(kSlope * (95 - kHorizon));

  Street() {
    for (int y = 0; y < kHeight; ++y) {
      if (y <= kHorizon) continue;
      disparity.row(y).setTo(kSlope * (y - kHorizon));
      measured.row(y).setTo(255);
    }
    disparity(object).setTo(object_disparity);
    measured(object).setTo(255);
  }
};

TEST(GroundPlane, TheDrawnGroundIsFoundWithItsSlopeAndHorizon) {
  const Street street;
  const GroundPlane ground = FitGroundPlane(street.disparity, street.measured);
  ASSERT_TRUE(ground.valid);
  EXPECT_NEAR(ground.slope, kSlope, 0.01);
  EXPECT_NEAR(ground.horizon_v, kHorizon, 1.0);
  // The object's pixels above its base are off the ground, the road's on it.
  const cv::Mat mask = GroundMask(street.disparity, street.measured, ground);
  EXPECT_EQ(mask.at<uint8_t>(60, 70), 0);  // the object, 35 rows above its base
  EXPECT_EQ(mask.at<uint8_t>(60, 20), 255);  // the road beside it
  EXPECT_EQ(mask.at<uint8_t>(110, 75), 255);  // the road below it
  EXPECT_EQ(mask.at<uint8_t>(20, 75), 0);    // the sky: not measured
}

TEST(GroundPlane, AWallFacingTheCameraIsNoGround) {
  // One disparity on every row: an upright surface, a vertical line in v-disparity.
  const cv::Mat disparity(kHeight, kWidth, CV_32FC1, cv::Scalar(12.f));
  const cv::Mat measured(kHeight, kWidth, CV_8UC1, cv::Scalar(255));
  EXPECT_FALSE(FitGroundPlane(disparity, measured).valid);
  // Nothing measured: no ground either.
  EXPECT_FALSE(FitGroundPlane(disparity, cv::Mat::zeros(kHeight, kWidth, CV_8UC1)).valid);
}

TEST(DepthContrast, AnObjectStandsOutAndTheGroundAndSkyDoNot) {
  const Street street;
  const GroundPlane ground = FitGroundPlane(street.disparity, street.measured);
  const cv::Mat contrast = DepthContrast(street.disparity, street.measured, ground, 41);
  // 35 rows above its base the ground's disparity is 0.25 x 20 = 5: the object, at 13.75, is
  // nearer by (13.75 - 5 - 1) / 13.75, the pixel of the matcher's noise taken off.
  EXPECT_NEAR(contrast.at<float>(60, 75), (street.object_disparity - 6.0) / street.object_disparity,
              0.02);
  EXPECT_LT(contrast.at<float>(60, 20), 0.1);   // the road
  EXPECT_LT(contrast.at<float>(115, 75), 0.1);  // the road near the camera: the nearest pixels
  EXPECT_EQ(contrast.at<float>(20, 75), 0.f);   // the sky
  // Nearness would rank the road's nearest rows first; contrast ranks the object first.
  double best = 0.0;
  cv::Point at;
  cv::minMaxLoc(contrast, nullptr, &best, nullptr, &at);
  EXPECT_TRUE(street.object.contains(at)) << at;
}

}  // namespace
}  // namespace attend
