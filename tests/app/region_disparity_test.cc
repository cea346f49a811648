// Per-region disparity against ground truth (app/region_disparity.h) on a pair whose disparity
// is known by construction: a red textured square at 9 px in front of a blue textured
// background at 3 px.
#include "app/region_disparity.h"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

namespace attend {
namespace {

constexpr int kWidth = 160, kHeight = 120;
const cv::Rect kSquare(60, 30, 60, 50);

void Pair(cv::Mat* left, cv::Mat* right, cv::Mat* truth) {
  cv::RNG rng(11);
  // The right view: a textured blue background with a textured red square at kSquare shifted
  // left by 9 (where the left view shows it at kSquare).
  cv::Mat texture(kHeight, kWidth, CV_8UC1);
  rng.fill(texture, cv::RNG::UNIFORM, 0, 90);
  *right = cv::Mat(kHeight, kWidth, CV_8UC3);
  *left = cv::Mat(kHeight, kWidth, CV_8UC3);
  *truth = cv::Mat(kHeight, kWidth, CV_32FC1);
  const cv::Rect in_right = kSquare - cv::Point(9, 0);
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      const uchar t = texture.at<uchar>(y, x);
      right->at<cv::Vec3b>(y, x) = in_right.contains({x, y}) ? cv::Vec3b(40, 40 + t / 2, 150 + t)
                                                             : cv::Vec3b(150 + t, 70 + t / 2, 40);
    }
  }
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      const int d = kSquare.contains({x, y}) ? 9 : 3;
      truth->at<float>(y, x) = x - d >= 0 ? static_cast<float>(d) : 0.f;
      left->at<cv::Vec3b>(y, x) = right->at<cv::Vec3b>(y, std::max(0, x - d));
    }
  }
}

TEST(RegionDisparity, EachLargeRegionIsScoredBothWays) {
  cv::Mat left, right, truth;
  Pair(&left, &right, &truth);
  DisparityOptions options;
  options.max_disparity = 16;
  cv::Mat disparity;
  DisparityEstimator(options).Compute(left, right, &disparity);
  const nlohmann::json report =
      ScoreRegionDisparities(left, right, disparity, truth, options, 0.01);
  ASSERT_GE(report["regions"].get<int>(), 2) << report.dump(1);
  // Every region's truth is one of the two planes'; both methods are within 1 px of it on
  // most regions (a region astride the square's edge can miss), and on the largest of each.
  int largest_area[2] = {0, 0};
  nlohmann::json largest[2];
  for (const nlohmann::json& region : report["per_region"]) {
    const double expected = region["truth_px"].get<double>();
    ASSERT_TRUE(expected == 9.0 || expected == 3.0) << region.dump();
    const int plane = expected == 9.0 ? 0 : 1;
    if (region["area"].get<int>() > largest_area[plane]) {
      largest_area[plane] = region["area"].get<int>();
      largest[plane] = region;
    }
  }
  for (const nlohmann::json& region : largest) {
    ASSERT_TRUE(region.is_object()) << report.dump(1);
    const double expected = region["truth_px"].get<double>();
    EXPECT_NEAR(region["map"]["disparity_px"].get<double>(), expected, 1.0) << region.dump();
    EXPECT_NEAR(region["template"]["disparity_px"].get<double>(), expected, 1.0) << region.dump();
  }
  EXPECT_GE(report["map"]["within_1px"].get<double>(), 0.75) << report.dump(1);
  EXPECT_GE(report["template"]["within_1px"].get<double>(), 0.75) << report.dump(1);
  // A threshold above every region leaves none.
  EXPECT_EQ(ScoreRegionDisparities(left, right, disparity, truth, options, 0.99)["regions"], 0);
}

}  // namespace
}  // namespace attend
