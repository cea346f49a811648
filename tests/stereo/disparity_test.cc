#include "stereo/disparity.h"
#include "stereo/disparity_internal.h"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>
#include <cstring>
#include <iostream>
#include <random>

#include "eval/disparity_scores.h"
#include "synth/renderer.h"
#include "synth/scene.h"
#include "tests/support/temp_dir.h"
#include "util/error.h"

namespace attend {
namespace {

// A random-dot right image and the left image that sees it through `truth`: the left pixel
// (x, y) shows the right pixel (x - truth(x, y), y). Dots are 8-bit noise, blurred a little so
// that sub-pixel shifts are meaningful.
struct Stereogram {
  cv::Mat left, right;
  cv::Mat truth;  // CV_32FC1
};

Stereogram MakeStereogram(const cv::Mat& truth, unsigned seed) {
  Stereogram s;
  s.truth = truth;
  s.right.create(truth.size(), CV_8UC1);
  cv::RNG rng(seed);
  rng.fill(s.right, cv::RNG::UNIFORM, 0, 256);
  s.left.create(truth.size(), CV_8UC1);
  for (int y = 0; y < truth.rows; ++y) {
    for (int x = 0; x < truth.cols; ++x) {
      const int source = x - static_cast<int>(truth.at<float>(y, x));
      s.left.at<uchar>(y, x) = s.right.at<uchar>(y, std::max(0, source));
    }
  }
  return s;
}

// Disparity 2 everywhere, 7 in a square.
cv::Mat SquareOnPlane(cv::Size size, cv::Rect square) {
  cv::Mat truth(size, CV_32FC1, cv::Scalar(2.f));
  truth(square).setTo(7.f);
  return truth;
}

TEST(Disparity, BoxFilteredZnccEqualsTheDirectComputation) {
  cv::Mat left(40, 50, CV_8UC1), right(40, 50, CV_8UC1);
  cv::RNG rng(5);
  rng.fill(left, cv::RNG::UNIFORM, 0, 256);
  rng.fill(right, cv::RNG::UNIFORM, 0, 256);
  for (const int window : {3, 5, 9}) {
    for (const int d : {0, 3, 11}) {
      cv::Mat slice;
      ZnccSlice(left, right, d, window, &slice);
      const int half = window / 2;
      for (int y = half; y < left.rows - half; ++y) {
        for (int x = d + half; x < left.cols - half; ++x) {
          ASSERT_NEAR(slice.at<float>(y, x), DirectZncc(left, right, x, y, d, window), 1e-5)
              << "window " << window << " d " << d << " at " << x << "," << y;
        }
      }
      EXPECT_EQ(slice.at<float>(5, d - 1 < 0 ? 0 : d - 1), d > 0 ? -1.f : slice.at<float>(5, 0));
    }
  }
}

TEST(Disparity, RandomDotSquareOnAPlaneIsExactAwayFromEdges) {
  const cv::Rect square(50, 30, 40, 30);
  const Stereogram s = MakeStereogram(SquareOnPlane(cv::Size(140, 100), square), 1);
  DisparityOptions options;
  options.max_disparity = 16;
  options.window = 7;
  DisparityEstimator estimator(options);
  cv::Mat disparity;
  estimator.Compute(s.left, s.right, &disparity);
  ASSERT_EQ(disparity.type(), CV_32FC1);
  ASSERT_EQ(disparity.size(), s.left.size());
  const int margin = options.window + 7;
  int wrong = 0, checked = 0;
  for (int y = margin; y < disparity.rows - margin; ++y) {
    for (int x = margin; x < disparity.cols - margin; ++x) {
      // Away from the square's edges, where windows straddle two disparities or see occlusion.
      const cv::Rect near_edge(square.x - margin, square.y - margin, square.width + 2 * margin,
                               square.height + 2 * margin);
      const cv::Rect inner(square.x + margin, square.y + margin, square.width - 2 * margin,
                           square.height - 2 * margin);
      const cv::Point p(x, y);
      if (near_edge.contains(p) && !inner.contains(p)) continue;
      ++checked;
      wrong += disparity.at<float>(y, x) != s.truth.at<float>(y, x);
    }
  }
  EXPECT_GT(checked, 3000);
  EXPECT_EQ(wrong, 0);
  EXPECT_EQ(disparity.at<float>(45, 70), 7.f);
}

TEST(Disparity, FollowsASlantedPlane) {
  // The disparity grows by one every 12 columns: 2 at the left to 11 at the right.
  cv::Mat truth(60, 120, CV_32FC1);
  for (int y = 0; y < truth.rows; ++y) {
    for (int x = 0; x < truth.cols; ++x) truth.at<float>(y, x) = 2.f + x / 12;
  }
  const Stereogram s = MakeStereogram(truth, 2);
  DisparityOptions options;
  options.max_disparity = 16;
  options.window = 7;
  DisparityEstimator estimator(options);
  cv::Mat disparity;
  estimator.Compute(s.left, s.right, &disparity);
  int off_by_more_than_one = 0, exact = 0, counted = 0;
  for (int y = 8; y < 52; ++y) {
    for (int x = 8; x < 112; ++x) {
      const float error = std::abs(disparity.at<float>(y, x) - truth.at<float>(y, x));
      off_by_more_than_one += error > 1.f;
      exact += error == 0.f;
      ++counted;
    }
  }
  EXPECT_EQ(off_by_more_than_one, 0);
  EXPECT_GT(exact, 0.85 * counted);
}

TEST(Disparity, InvariantToGainAndOffsetOfTheRightImage) {
  const Stereogram s = MakeStereogram(SquareOnPlane(cv::Size(100, 70), {30, 20, 30, 25}), 3);
  cv::Mat brighter;
  s.right.convertTo(brighter, CV_8U, 0.6, 40.0);  // stays within 0..255: no clipping
  DisparityOptions options;
  options.max_disparity = 12;
  options.window = 9;
  DisparityEstimator estimator(options);
  cv::Mat a, b;
  estimator.Compute(s.left, s.right, &a);
  estimator.Compute(s.left, brighter, &b);
  // Rounding the scaled image to integers perturbs the ZNCC slightly; the maps agree where the
  // correlation peak is clear, which is nearly everywhere.
  cv::Mat differ = a != b;
  EXPECT_LT(cv::countNonZero(differ), 0.01 * a.total());
}

TEST(Disparity, SubpixelRefinesTowardsFractionalTruth) {
  // A plane at disparity 4.5 in the left image made by averaging two integer shifts.
  cv::Mat right(60, 100, CV_8UC1);
  cv::RNG(4).fill(right, cv::RNG::UNIFORM, 0, 256);
  cv::GaussianBlur(right, right, cv::Size(5, 5), 1.2);
  cv::Mat left(right.size(), CV_8UC1);
  for (int y = 0; y < right.rows; ++y) {
    for (int x = 0; x < right.cols; ++x) {
      const int a = std::max(0, x - 4), b = std::max(0, x - 5);
      left.at<uchar>(y, x) =
          static_cast<uchar>((right.at<uchar>(y, a) + right.at<uchar>(y, b) + 1) / 2);
    }
  }
  DisparityOptions options;
  options.max_disparity = 10;
  options.subpixel = true;
  DisparityEstimator estimator(options);
  cv::Mat disparity;
  estimator.Compute(left, right, &disparity);
  const cv::Scalar mean = cv::mean(disparity(cv::Rect(15, 10, 70, 40)));
  EXPECT_NEAR(mean[0], 4.5, 0.15);
  options.subpixel = false;
  DisparityEstimator integer(options);
  integer.Compute(left, right, &disparity);
  cv::Mat fractional = (disparity != 4.f) & (disparity != 5.f);
  EXPECT_EQ(cv::countNonZero(fractional(cv::Rect(15, 10, 70, 40))), 0);
}

TEST(Disparity, LeftRightCheckMarksInconsistentPixels) {
  // Left row: 2 2 2 7 7; right view: 2 2 2 2 2. Pixel 3 (d 7) would match x = -4: invalid;
  // pixel 4 matches x = -3: invalid; pixels 0 and 1 match outside too; pixel 2 matches 0.
  cv::Mat left = (cv::Mat_<float>(1, 5) << 2.f, 2.f, 2.f, 7.f, 7.f);
  const cv::Mat right = (cv::Mat_<float>(1, 5) << 2.f, 2.f, 2.f, 2.f, 2.f);
  CheckLeftRight(right, 1, &left);
  const cv::Mat expected = (cv::Mat_<float>(1, 5) << -1.f, -1.f, 2.f, -1.f, -1.f);
  EXPECT_EQ(cv::norm(left, expected, cv::NORM_INF), 0.0);
  // Within the tolerance the pixel stays.
  cv::Mat close = (cv::Mat_<float>(1, 4) << 0.f, 0.f, 1.f, 1.f);
  const cv::Mat right_close = (cv::Mat_<float>(1, 4) << 0.f, 0.f, 1.f, 2.f);
  CheckLeftRight(right_close, 1, &close);
  EXPECT_EQ(close.at<float>(0, 3), 1.f);  // matches x = 2, right says 1
  CheckLeftRight(right_close, 0, &close);
  EXPECT_EQ(close.at<float>(0, 2), -1.f);  // matches x = 1, right says 0
}

TEST(Disparity, FillTakesTheFartherNeighbour) {
  cv::Mat row = (cv::Mat_<float>(1, 8) << -1.f, 3.f, -1.f, -1.f, 5.f, -1.f, 2.f, -1.f);
  FillInvalidDisparities(&row);
  const cv::Mat expected = (cv::Mat_<float>(1, 8) << 3.f, 3.f, 3.f, 3.f, 5.f, 2.f, 2.f, 2.f);
  EXPECT_EQ(cv::norm(row, expected, cv::NORM_INF), 0.0);
  cv::Mat empty(1, 3, CV_32FC1, cv::Scalar(-1.f));
  FillInvalidDisparities(&empty);
  EXPECT_EQ(cv::countNonZero(empty), 0);
}

TEST(Disparity, LeftRightCheckKeepsAConsistentMapAndFillsFromTheBackground) {
  const cv::Rect square(50, 30, 40, 30);
  const Stereogram s = MakeStereogram(SquareOnPlane(cv::Size(140, 100), square), 6);
  DisparityOptions options;
  options.max_disparity = 16;
  options.window = 7;
  DisparityEstimator plain(options);
  options.left_right_check = true;
  DisparityEstimator checked(options);
  cv::Mat a, b;
  plain.Compute(s.left, s.right, &a);
  checked.Compute(s.left, s.right, &b);
  double low = 0;
  cv::minMaxLoc(b, &low);
  EXPECT_GE(low, 0.0);
  // Where the plain map is right away from the square's edges, the check keeps it.
  const cv::Rect inner(square.x + 8, square.y + 8, square.width - 16, square.height - 16);
  EXPECT_EQ(cv::norm(a(inner), b(inner), cv::NORM_INF), 0.0);
  // The occluded band left of the square (5 columns) is no farther from the truth than before.
  const cv::Rect band(square.x - 5, square.y + 8, 5, square.height - 16);
  EXPECT_LE(EvaluateDisparity(b(band).clone(), s.truth(band).clone()).bad1,
            EvaluateDisparity(a(band).clone(), s.truth(band).clone()).bad1);
}

TEST(Disparity, SynthGroundTruthBadPixelRateIsBounded) {
  const SceneRenderer renderer(LoadScene(testing::ProjectRoot() + "/sequences/lab.yaml"));
  const RenderedFrame frame = renderer.Render(30);
  // The thesis's settings: hard smoothness, no left-right check, window 9, no median.
  DisparityOptions options;
  options.max_disparity = 48;
  options.smoothness = DisparitySmoothness::kHard;
  options.window = 9;
  options.left_right_check = false;
  options.median = 0;
  DisparityEstimator estimator(options);
  cv::Mat disparity;
  estimator.Compute(frame.left, frame.right, &disparity);
  const BadPixelRates rates = EvaluateDisparity(disparity, frame.disparity);
  EXPECT_EQ(rates.known, static_cast<int>(frame.disparity.total()));
  // The stated bounds (docs/DISPARITY.md) for frame 30 of the bundled scene: at most 14% of
  // the pixels off by more than 1 px with the thesis's settings, mostly the ramps that the
  // |delta d| <= 1 constraint puts at depth edges; at most 9% with the hard smoothness, window
  // 7 and the left-right check (the defaults before sgm, which the attention loop keeps); at
  // most 7% with the penalty smoothness as well; at most 5% with the defaults (sgm).
  EXPECT_LT(rates.bad1, 0.14) << rates.bad1;
  EXPECT_LE(rates.bad2, rates.bad1);
  DisparityOptions hard;
  hard.max_disparity = 48;
  hard.smoothness = DisparitySmoothness::kHard;
  hard.window = 7;
  hard.median = 0;
  DisparityEstimator checked(hard);
  checked.Compute(frame.left, frame.right, &disparity);
  const double hard_bad1 = EvaluateDisparity(disparity, frame.disparity).bad1;
  EXPECT_LT(hard_bad1, 0.09);
  hard.smoothness = DisparitySmoothness::kPenalty;
  DisparityEstimator penalty(hard);
  penalty.Compute(frame.left, frame.right, &disparity);
  EXPECT_LT(EvaluateDisparity(disparity, frame.disparity).bad1, 0.07);
  DisparityOptions defaults;
  defaults.max_disparity = 48;
  DisparityEstimator semi_global(defaults);
  semi_global.Compute(frame.left, frame.right, &disparity);
  const double sgm_bad1 = EvaluateDisparity(disparity, frame.disparity).bad1;
  std::cout << "lab frame 30, bad1: thesis " << rates.bad1 << ", hard " << hard_bad1 << ", sgm "
            << sgm_bad1 << "\n";
  EXPECT_LT(sgm_bad1, 0.05);
}

// The AVX2 kernels must give the portable kernels' maps bit for bit, for every mode and for
// ranges that are and are not multiples of the kernels' eight lanes.
TEST(Disparity, Avx2KernelsGiveThePortableKernelsMaps) {
#if defined(__x86_64__) && defined(__GNUC__)
  if (!__builtin_cpu_supports("avx2")) GTEST_SKIP() << "this processor has no AVX2";
#else
  GTEST_SKIP() << "the AVX2 kernels exist only on x86-64";
#endif
  const SceneRenderer renderer(LoadScene(testing::ProjectRoot() + "/sequences/lab.yaml"));
  const RenderedFrame frame = renderer.Render(30);
  struct Case {
    int max_disparity;
    DisparitySmoothness smoothness;
    bool subpixel, left_right_check;
  };
  const Case cases[] = {{32, DisparitySmoothness::kHard, false, true},
                        {37, DisparitySmoothness::kHard, false, false},
                        {13, DisparitySmoothness::kPenalty, true, true},
                        {64, DisparitySmoothness::kPenalty, false, true},
                        {5, DisparitySmoothness::kHard, true, false},
                        // sgm's costs: 32 and 16 at a time and the rest one by one.
                        {48, DisparitySmoothness::kSgm, false, true},
                        {20, DisparitySmoothness::kSgm, true, true},
                        {64, DisparitySmoothness::kSgm, false, false}};
  for (const Case& c : cases) {
    DisparityOptions options;
    options.max_disparity = c.max_disparity;
    options.smoothness = c.smoothness;
    options.jump_penalty = 0.5f;
    options.subpixel = c.subpixel;
    options.left_right_check = c.left_right_check;
    cv::Mat maps[2];
    for (int portable = 0; portable < 2; ++portable) {
      UsePortableDisparityKernels(portable == 1);
      DisparityEstimator estimator(options);
      estimator.Compute(frame.left, frame.right, &maps[portable]);
    }
    UsePortableDisparityKernels(false);
    ASSERT_EQ(maps[0].size(), maps[1].size());
    const size_t bytes = maps[0].total() * maps[0].elemSize();
    EXPECT_EQ(std::memcmp(maps[0].data, maps[1].data, bytes), 0)
        << "D " << c.max_disparity << ", " << DisparitySmoothnessName(c.smoothness)
        << ", subpixel " << c.subpixel << ", left-right check " << c.left_right_check;
    // A map of a real scene, not a constant one: the comparison means something.
    double low = 0, high = 0;
    cv::minMaxLoc(maps[0], &low, &high);
    EXPECT_GT(high - low, 3.0);
  }
}

// An estimator keeps its buffers between pairs: a pair of another size after the first, and the
// first again after it, give the maps a fresh estimator gives.
TEST(Disparity, AReusedEstimatorGivesAFreshOnesMaps) {
  const SceneRenderer renderer(LoadScene(testing::ProjectRoot() + "/sequences/lab.yaml"));
  const RenderedFrame a = renderer.Render(10);
  const RenderedFrame b = renderer.Render(40);
  cv::Mat b_left, b_right;
  cv::resize(b.left, b_left, cv::Size(), 0.75, 0.5, cv::INTER_AREA);
  cv::resize(b.right, b_right, cv::Size(), 0.75, 0.5, cv::INTER_AREA);
  for (const DisparitySmoothness smoothness :
       {DisparitySmoothness::kSgm, DisparitySmoothness::kHard}) {
    DisparityOptions options;
    options.smoothness = smoothness;
    options.max_disparity = 32;
    DisparityEstimator reused(options);
    cv::Mat map;
    reused.Compute(a.left, a.right, &map);
    cv::Mat second, fresh_map;
    reused.Compute(b_left, b_right, &second);
    DisparityEstimator fresh(options);
    fresh.Compute(b_left, b_right, &fresh_map);
    ASSERT_EQ(second.size(), b_left.size());
    EXPECT_EQ(cv::countNonZero(second != fresh_map), 0) << DisparitySmoothnessName(smoothness);
    // And the first size again, after the smaller one.
    cv::Mat again, fresh_again;
    reused.Compute(a.left, a.right, &again);
    DisparityEstimator(options).Compute(a.left, a.right, &fresh_again);
    EXPECT_EQ(cv::countNonZero(again != fresh_again), 0) << DisparitySmoothnessName(smoothness);
  }
}

// A pair wider than max_width is computed halved: the map has the pair's size, its values are
// even (the half-size disparities doubled) and follow the truth within the factor.
TEST(Disparity, WidePairsAreComputedAtMaxWidth) {
  const cv::Mat truth = SquareOnPlane(cv::Size(256, 96), cv::Rect(96, 24, 64, 48));
  truth *= 2.0;  // 4 on the plane, 14 on the square: even, so exact at half size
  const Stereogram s = MakeStereogram(truth, 11);
  DisparityOptions options;
  options.max_disparity = 24;
  options.left_right_check = false;
  cv::Mat full, halved;
  DisparityEstimator(options).Compute(s.left, s.right, &full);
  options.max_width = 128;
  DisparityEstimator estimator(options);
  estimator.Compute(s.left, s.right, &halved);
  ASSERT_EQ(halved.size(), s.left.size());
  int odd = 0, off = 0, inside = 0;
  for (int y = 8; y < truth.rows - 8; ++y) {
    for (int x = 24; x < truth.cols - 8; ++x) {
      const float d = halved.at<float>(y, x);
      odd += static_cast<int>(d) % 2 != 0;
      off += std::abs(d - truth.at<float>(y, x)) > 2.f;
      ++inside;
    }
  }
  EXPECT_EQ(odd, 0);
  EXPECT_LT(off, inside / 10) << "of " << inside;
  // Its buffers are those of the half-size pair, not of the full one.
  EXPECT_GT(halved.at<float>(48, 128), 10.f);
  // Not wider than max_width: the full-size computation, bit for bit.
  options.max_width = 256;
  cv::Mat same;
  DisparityEstimator(options).Compute(s.left, s.right, &same);
  EXPECT_EQ(cv::norm(same, full, cv::NORM_INF), 0.0);
}

TEST(Disparity, BadInputIsReported) {
  DisparityEstimator estimator;
  cv::Mat out;
  EXPECT_THROW(estimator.Compute(cv::Mat(10, 40, CV_8UC1), cv::Mat(11, 40, CV_8UC1), &out),
               InputError);
  EXPECT_THROW(estimator.Compute(cv::Mat(10, 32, CV_8UC1), cv::Mat(10, 32, CV_8UC1), &out),
               InputError);  // D = 32 is not below the width
  DisparityOptions options;
  options.window = 4;
  EXPECT_THROW(DisparityEstimator{options}, ConfigError);
}

TEST(Disparity, BadPixelRatesCountInvalidAsBad) {
  const cv::Mat truth = (cv::Mat_<float>(1, 5) << 0.f, 3.f, 3.f, 3.f, 3.f);
  const cv::Mat estimate = (cv::Mat_<float>(1, 5) << 9.f, 3.5f, 4.5f, 6.f, -1.f);
  const BadPixelRates rates = EvaluateDisparity(estimate, truth);
  EXPECT_EQ(rates.known, 4);              // 0 is unknown
  EXPECT_DOUBLE_EQ(rates.bad1, 3.0 / 4);  // 4.5, 6 and the invalid -1
  EXPECT_DOUBLE_EQ(rates.bad2, 2.0 / 4);  // 6 and -1
}

}  // namespace
}  // namespace attend
