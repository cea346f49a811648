// Each target's disparity (semiattentive/target_depth.h) on pairs whose disparity is known by
// construction: a textured right view made from the left by a sub-pixel shift, disparity maps
// with outliers, the low-pass filter's steady state and noise gain, and the triangulation.
#include "semiattentive/target_depth.h"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgproc.hpp>
#include <random>

namespace attend {
namespace {

// A left view of coloured blocks of random texture (smoothed so that sub-pixel shifts
// interpolate), and a right view that shows each left pixel (x, y) at (x - d, y).
void ShiftedPair(double d, cv::Mat* left, cv::Mat* right) {
  cv::Mat noise(120, 200, CV_8UC3);
  cv::RNG rng(7);
  rng.fill(noise, cv::RNG::UNIFORM, 0, 256);
  cv::GaussianBlur(noise, *left, cv::Size(5, 5), 1.2);
  cv::normalize(*left, *left, 0, 255, cv::NORM_MINMAX);
  const cv::Mat shift = (cv::Mat_<double>(2, 3) << 1, 0, -d, 0, 1, 0);
  cv::warpAffine(*left, *right, shift, left->size(), cv::INTER_LINEAR, cv::BORDER_REFLECT);
}

cv::Mat BoxMask(cv::Size size, const cv::Rect& box) {
  cv::Mat mask = cv::Mat::zeros(size, CV_8UC1);
  mask(box).setTo(255);
  return mask;
}

TEST(TemplateDisparity, FindsASubPixelShiftOfATexturedTarget) {
  DepthOptions options;
  options.method = TargetDisparityMethod::kTemplate;
  for (const double d : {4.0, 7.3, 11.6, 20.5}) {
    cv::Mat left, right;
    ShiftedPair(d, &left, &right);
    const cv::Rect box(80, 30, 60, 50);
    const DisparityEstimate estimate =
        TemplateDisparity(left, right, BoxMask(left.size(), box), box, 32, options, 5);
    ASSERT_TRUE(estimate.valid()) << d;
    EXPECT_NEAR(estimate.disparity, d, 0.25) << d;
    EXPECT_GT(estimate.sd, 0.0);
    EXPECT_LT(estimate.sd, 0.5) << d;
  }
}

TEST(TemplateDisparity, OnlyTheMaskCounts) {
  // The right view's left half is shifted by 6, its right half by 14; a mask on either half
  // finds its own.
  cv::Mat left, right6, right14;
  ShiftedPair(6, &left, &right6);
  ShiftedPair(14, &left, &right14);
  cv::Mat right = right6.clone();
  right14(cv::Rect(100, 0, 100, 120)).copyTo(right(cv::Rect(100, 0, 100, 120)));
  DepthOptions options;
  const cv::Rect near(130, 20, 60, 80), far(30, 20, 60, 80);
  EXPECT_NEAR(TemplateDisparity(left, right, BoxMask(left.size(), near), near, 32, options, 5)
                  .disparity, 14, 0.3);
  EXPECT_NEAR(TemplateDisparity(left, right, BoxMask(left.size(), far), far, 32, options, 5)
                  .disparity, 6, 0.3);
}

TEST(TemplateDisparity, AnEmptyMaskHasNoEstimate) {
  cv::Mat left, right;
  ShiftedPair(5, &left, &right);
  const cv::Mat empty = cv::Mat::zeros(left.size(), CV_8UC1);
  EXPECT_FALSE(TemplateDisparity(left, right, empty, cv::Rect(0, 0, 50, 50), 32, {}, 5).valid());
}

TEST(TemplateDisparity, AFlatTargetIsUncertain) {
  // A uniform grey target matches at every shift: whatever the shift, its sd is large.
  cv::Mat left(60, 120, CV_8UC3, cv::Scalar(90, 90, 90)), right = left.clone();
  const cv::Rect box(60, 10, 40, 40);
  const DisparityEstimate estimate =
      TemplateDisparity(left, right, BoxMask(left.size(), box), box, 32, {}, 5);
  ASSERT_TRUE(estimate.valid());
  EXPECT_GE(estimate.sd, 1.0);
}

TEST(MapDisparity, IgnoresOutliersAndIsSubPixelOnAnIntegerMap) {
  cv::Mat map(100, 100, CV_32FC1, cv::Scalar(12.f));
  map(cv::Rect(0, 0, 100, 10)).setTo(40.f);  // 10 % outliers
  map(cv::Rect(0, 90, 100, 10)).setTo(-1.f);  // invalid
  const cv::Rect box(0, 0, 100, 100);
  const cv::Mat mask = BoxMask(map.size(), box);
  DisparityEstimate estimate = MapDisparity(map, mask, box, {}, 5);
  EXPECT_NEAR(estimate.disparity, 12.0, 1e-6);
  EXPECT_GT(estimate.sd, 0.0);
  // Half 5s and half 6s: between the two.
  map.setTo(5.f);
  map(cv::Rect(0, 0, 100, 50)).setTo(6.f);
  estimate = MapDisparity(map, mask, box, {}, 5);
  EXPECT_NEAR(estimate.disparity, 5.5, 0.01);
  EXPECT_FALSE(MapDisparity(map, cv::Mat::zeros(map.size(), CV_8UC1), box, {}, 5).valid());
}

// Depth only where it was measured: a thin object (10 px of a 40 px box) in front of a wall
// whose filled pixels hold the wall's disparity. Over the measured pixels the object's own
// disparity; with too few measured, no estimate, marked unmeasured; min_measured 0 reads every
// pixel as before.
TEST(MapDisparity, ReadsOnlyTheMeasuredPixelsAndRefusesTooFew) {
  cv::Mat map(60, 60, CV_32FC1, cv::Scalar(4.f));  // the wall behind, filled in
  map(cv::Rect(10, 10, 40, 40)).setTo(4.f);
  map(cv::Rect(10, 10, 40, 8)).setTo(20.f);  // the object's measured rows
  cv::Mat measured = cv::Mat::zeros(map.size(), CV_8UC1);
  measured(cv::Rect(10, 10, 40, 8)).setTo(255);  // 20 % of the box
  const cv::Rect box(10, 10, 40, 40);
  const cv::Mat mask = BoxMask(map.size(), box);
  DepthOptions options;
  DisparityEstimate estimate = MapDisparity(map, mask, box, options, 5, measured);
  ASSERT_TRUE(estimate.valid());
  EXPECT_NEAR(estimate.disparity, 20.0, 1e-6);
  EXPECT_FALSE(estimate.unmeasured);
  // Every pixel, the filled ones too: the wall's value wins the interquartile mean.
  options.min_measured = 0.f;
  EXPECT_NEAR(MapDisparity(map, mask, box, options, 5, measured).disparity, 4.0, 1e-6);
  // 10 % measured, under min_measured 0.2: none.
  options.min_measured = 0.2f;
  measured.setTo(0);
  measured(cv::Rect(10, 10, 40, 4)).setTo(255);
  estimate = MapDisparity(map, mask, box, options, 5, measured);
  EXPECT_FALSE(estimate.valid());
  EXPECT_TRUE(estimate.unmeasured);
}

TEST(LowPass4, StartsInItsSteadyStateAndPassesAConstant) {
  LowPass4 filter(0.1);
  for (int i = 0; i < 20; ++i) EXPECT_NEAR(filter.Step(7.5), 7.5, 1e-9);
}

TEST(LowPass4, FollowsAStepAndDampsNoise) {
  LowPass4 filter(0.1);
  filter.Step(0.0);
  double y = 0.0;
  for (int i = 0; i < 60; ++i) y = filter.Step(1.0);
  EXPECT_NEAR(y, 1.0, 0.01);
  EXPECT_GT(filter.NoiseGain(), 0.05);
  EXPECT_LT(filter.NoiseGain(), 0.4);
  // Noise of sd 1 about 3 comes out with about sqrt(NoiseGain) of it.
  LowPass4 noisy(0.1);
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(3.0, 1.0);
  double sum2 = 0.0;
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    const double out = noisy.Step(noise(rng));
    if (i >= 100) sum2 += (out - 3.0) * (out - 3.0);
  }
  EXPECT_NEAR(std::sqrt(sum2 / (n - 100)), std::sqrt(noisy.NoiseGain()), 0.05);
}

TEST(LowPass4, ACutoffOfHalfTheRateIsNoFilter) {
  LowPass4 none(0.5);
  EXPECT_DOUBLE_EQ(none.Step(1.0), 1.0);
  EXPECT_DOUBLE_EQ(none.Step(5.0), 5.0);
  EXPECT_DOUBLE_EQ(none.NoiseGain(), 1.0);
}

TEST(Triangulate, GivesThePositionAndItsUncertainty) {
  Position3d p;
  // f 500 px, B 0.1 m, d 10 px: Z = 5 m; 100 px right of and 50 px above the centre.
  ASSERT_TRUE(Triangulate(500, 320, 240, 0.1, {420, 190}, {10.0, 0.5}, &p));
  EXPECT_NEAR(p.m[2], 5.0, 1e-12);
  EXPECT_NEAR(p.m[0], 1.0, 1e-12);
  EXPECT_NEAR(p.m[1], -0.5, 1e-12);
  EXPECT_NEAR(p.sd_m[2], 0.25, 1e-12);
  EXPECT_NEAR(p.sd_m[0], 0.05, 1e-12);
  EXPECT_FALSE(Triangulate(500, 320, 240, 0.1, {420, 190}, {0.0, 0.5}, &p));
  EXPECT_FALSE(Triangulate(500, 320, 240, 0.1, {420, 190}, {}, &p));
}

TEST(TargetDepths, FiltersEachTargetOnItsOwnAndForgets) {
  DepthOptions options;
  options.low_pass = 0.2f;
  TargetDepths depths(options);
  EXPECT_NEAR(depths.Update(1, {10.0, 0.2}).disparity, 10.0, 1e-9);
  EXPECT_NEAR(depths.Update(2, {4.0, 0.2}).disparity, 4.0, 1e-9);
  const DisparityEstimate moved = depths.Update(1, {12.0, 0.2});
  EXPECT_GT(moved.disparity, 10.0);
  EXPECT_LT(moved.disparity, 12.0);
  EXPECT_GT(moved.sd, 0.2 * std::sqrt(LowPass4(0.2).NoiseGain()));  // the spread adds
  // An invalid estimate keeps the last one.
  EXPECT_DOUBLE_EQ(depths.Update(1, {}).disparity, moved.disparity);
  depths.Forget(1);
  EXPECT_FALSE(depths.Last(1).valid());
  EXPECT_NEAR(depths.Last(2).disparity, 4.0, 1e-9);
}

}  // namespace
}  // namespace attend

namespace attend {
namespace {

// depth.jump_px's test: a target whose template estimate moves from 6 to 14 px between frames
// jumps by 8; one that stays does not.
TEST(TargetDepths, AJumpOfTheTemplateEstimateIsMeasured) {
  cv::Mat left, right6, right14;
  ShiftedPair(6, &left, &right6);
  ShiftedPair(14, &left, &right14);
  const cv::Rect box(80, 30, 60, 50);
  const cv::Mat mask = BoxMask(left.size(), box);
  DepthOptions options;  // map records; the jump is the template's all the same
  TargetDepths depths(options);
  StereoInput stereo;
  stereo.right = right6;
  stereo.max_disparity = 32;
  EXPECT_DOUBLE_EQ(depths.JumpOf(1, left, stereo, mask, box, {}), 0.0);  // its first frame
  EXPECT_LT(depths.JumpOf(1, left, stereo, mask, box, {}), 0.3);
  stereo.right = right14;
  EXPECT_NEAR(depths.JumpOf(1, left, stereo, mask, box, {}), 8.0, 0.5);
  depths.Forget(1);
  EXPECT_DOUBLE_EQ(depths.JumpOf(1, left, stereo, mask, box, {}), 0.0);  // starts again
}

}  // namespace
}  // namespace attend
