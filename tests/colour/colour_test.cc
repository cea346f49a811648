#include "colour/colour.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace attend {
namespace {

constexpr float kTolerance = 1e-3f;

TEST(Colour, CylinderOfPrimariesAndGreys) {
  // Red: H = 0, S = 255, V = 255.
  CylinderColour c = CylinderFromRgb(255, 0, 0);
  EXPECT_NEAR(c.sx, 255.f, kTolerance);
  EXPECT_NEAR(c.sy, 0.f, kTolerance);
  EXPECT_NEAR(c.v, 255.f, kTolerance);
  // Green: H = 120 degrees.
  c = CylinderFromRgb(0, 255, 0);
  EXPECT_NEAR(c.sx, 255.f * std::cos(2.0 * M_PI / 3.0), 1e-2);
  EXPECT_NEAR(c.sy, 255.f * std::sin(2.0 * M_PI / 3.0), 1e-2);
  // Blue: H = 240 degrees.
  c = CylinderFromRgb(0, 0, 255);
  EXPECT_NEAR(c.sx, 255.f * std::cos(4.0 * M_PI / 3.0), 1e-2);
  EXPECT_NEAR(c.sy, 255.f * std::sin(4.0 * M_PI / 3.0), 1e-2);
  // Greys and black have no chromatic phasor.
  c = CylinderFromRgb(90, 90, 90);
  EXPECT_EQ(c.sx, 0.f);
  EXPECT_EQ(c.sy, 0.f);
  EXPECT_EQ(c.v, 90.f);
  c = CylinderFromRgb(0, 0, 0);
  EXPECT_EQ(c.sx, 0.f);
  EXPECT_EQ(c.v, 0.f);
  // S = 1 - 3 min / sum: (200, 100, 100) has S = 1 - 300/400 = 0.25.
  EXPECT_NEAR(Saturation(CylinderFromRgb(200, 100, 100)), 0.25f * 255.f, kTolerance);
}

TEST(Colour, CylinderDistanceIsEuclideanBetweenVectors) {
  const CylinderColour red = CylinderFromRgb(255, 0, 0), green = CylinderFromRgb(0, 255, 0);
  // Same S and V, hues 120 degrees apart: chord 2 S sin(60) = S sqrt(3).
  EXPECT_NEAR(CylinderDistance(red, green), 255.f * std::sqrt(3.f), 1e-2);
  EXPECT_NEAR(CylinderDistance(CylinderFromRgb(10, 10, 10), CylinderFromRgb(40, 40, 40)), 30.f,
              kTolerance);
  EXPECT_EQ(CylinderDistance(red, red), 0.f);
}

TEST(Colour, ImageConversionsMatchThePerPixelFormulas) {
  cv::Mat bgr(7, 9, CV_8UC3);
  cv::randu(bgr, 0, 256);
  cv::Mat cylinder, tsl;
  BgrToCylinder(bgr, &cylinder);
  BgrToTsl(bgr, &tsl);
  ASSERT_EQ(cylinder.type(), CV_32FC3);
  for (int row = 0; row < bgr.rows; ++row) {
    for (int col = 0; col < bgr.cols; ++col) {
      const cv::Vec3b p = bgr.at<cv::Vec3b>(row, col);
      const CylinderColour c = CylinderFromRgb(p[2], p[1], p[0]);
      const cv::Vec3f got = cylinder.at<cv::Vec3f>(row, col);
      EXPECT_FLOAT_EQ(got[0], c.sx);
      EXPECT_FLOAT_EQ(got[1], c.sy);
      EXPECT_FLOAT_EQ(got[2], c.v);
      const cv::Vec2f ts = TslChrominance(p[2], p[1], p[0]);
      EXPECT_FLOAT_EQ(tsl.at<cv::Vec3f>(row, col)[0], ts[0]);
      EXPECT_FLOAT_EQ(tsl.at<cv::Vec3f>(row, col)[1], ts[1]);
      EXPECT_NEAR(tsl.at<cv::Vec3f>(row, col)[2], 0.299f * p[2] + 0.587f * p[1] + 0.114f * p[0],
                  1e-3);
    }
  }
}

TEST(Colour, TslOfKnownColours) {
  // Grey: r' = g' = 0, so T = 0 (g' = 0) and S = 0.
  cv::Vec2f ts = TslChrominance(50, 50, 50);
  EXPECT_NEAR(ts[0], 0.f, kTolerance);
  EXPECT_NEAR(ts[1], 0.f, kTolerance);
  // Red: r' = 2/3, g' = -1/3 < 0: T = atan(-2) / 2pi + 3/4, S = sqrt(9/5 (4/9 + 1/9)) = 1.
  ts = TslChrominance(255, 0, 0);
  EXPECT_NEAR(ts[0], std::atan(-2.0) / (2 * M_PI) + 0.75, 1e-5);
  EXPECT_NEAR(ts[1], 255.f, 1e-2);
  // Green: r' = -1/3, g' = 2/3 > 0: T = atan(-1/2) / 2pi + 1/4.
  ts = TslChrominance(0, 255, 0);
  EXPECT_NEAR(ts[0], std::atan(-0.5) / (2 * M_PI) + 0.25, 1e-5);
}

// The conversion uses its own arctangent (a series after two range reductions, so that it
// vectorises); it must agree with the double-precision formula on every colour of a grid.
TEST(Colour, TslMatchesTheDoublePrecisionFormula) {
  cv::Mat bgr(1, 52 * 52 * 52, CV_8UC3);
  int i = 0;
  for (int r = 0; r < 256; r += 5) {
    for (int g = 0; g < 256; g += 5) {
      for (int b = 0; b < 256; b += 5) bgr.at<cv::Vec3b>(0, i++) = cv::Vec3b(b, g, r);
    }
  }
  cv::Mat tsl;
  BgrToTsl(bgr, &tsl);
  double worst_t = 0.0, worst_s = 0.0;
  for (int k = 0; k < bgr.cols; ++k) {
    const cv::Vec3b p = bgr.at<cv::Vec3b>(0, k);
    const double sum = p[0] + p[1] + p[2];
    double t = 0.0, s = 0.0;
    if (sum > 0) {
      const double rp = p[2] / sum - 1.0 / 3.0, gp = p[1] / sum - 1.0 / 3.0;
      s = 255.0 * std::sqrt(9.0 / 5.0 * (rp * rp + gp * gp));
      if (gp != 0.0) t = std::atan(rp / gp) / (2 * M_PI) + (gp > 0 ? 0.25 : 0.75);
    }
    const cv::Vec3f got = tsl.at<cv::Vec3f>(0, k);
    // Where g' is 0 in exact arithmetic (3G = R + G + B), T is 0 by definition but jumps to
    // 0.5 or 1 for a rounding residue of either sign, in float as in double: skip those.
    if (3 * p[1] != sum) {
      worst_t = std::max(worst_t, std::abs(got[0] - t));
    } else {
      EXPECT_EQ(got[0], 0.f) << "SPEC 2.1: T = 0 where g' = 0";
    }
    worst_s = std::max(worst_s, std::abs(got[1] - s));
  }
  EXPECT_LT(worst_t, 2e-6);
  EXPECT_LT(worst_s, 1e-3);
}

TEST(Colour, RgbFromCylinderInvertsTheConversion) {
  std::mt19937 random(3);
  std::uniform_int_distribution<int> channel(0, 255);
  for (int i = 0; i < 1000; ++i) {
    const float r = channel(random), g = channel(random), b = channel(random);
    const cv::Vec3f back = RgbFromCylinder(CylinderFromRgb(r, g, b));
    EXPECT_NEAR(back[0], r, 0.05) << r << " " << g << " " << b;
    EXPECT_NEAR(back[1], g, 0.05) << r << " " << g << " " << b;
    EXPECT_NEAR(back[2], b, 0.05) << r << " " << g << " " << b;
  }
}

}  // namespace
}  // namespace attend
