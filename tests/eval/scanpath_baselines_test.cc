// The scanpath baselines (eval/scanpath_baselines.h): centre-bias draws and a map's peaks, on
// maps whose peaks are known by construction.
#include "eval/scanpath_baselines.h"

#include <gtest/gtest.h>

#include <cmath>

namespace attend {
namespace {

TEST(CentreBiasScanpath, DrawsInsideTheImageAroundTheCentreAndRepeatsForASeed) {
  const cv::Size image(400, 200);
  cv::RNG rng(7);
  const Scanpath path = CentreBiasScanpath(image, 5000, 0.25, &rng);
  ASSERT_EQ(path.size(), 5000u);
  double mean_x = 0.0, mean_y = 0.0;
  for (const Fixation& f : path) {
    EXPECT_GE(f.x, -0.5);
    EXPECT_LT(f.x, 399.5);
    EXPECT_GE(f.y, -0.5);
    EXPECT_LT(f.y, 199.5);
    EXPECT_DOUBLE_EQ(f.duration_s, 0.25);
    mean_x += f.x / path.size();
    mean_y += f.y / path.size();
  }
  EXPECT_NEAR(mean_x, 199.5, 4.0);
  EXPECT_NEAR(mean_y, 99.5, 2.0);
  cv::RNG again(7), other(8);
  const Scanpath first = CentreBiasScanpath(image, 3, 0.25, &again);
  EXPECT_DOUBLE_EQ(first[0].x, path[0].x);
  EXPECT_DOUBLE_EQ(first[2].y, path[2].y);
  EXPECT_NE(CentreBiasScanpath(image, 1, 0.25, &other)[0].x, path[0].x);
}

TEST(SaliencyPeaks, AreLocalMaximaInOrderOfHeightAtLeastTheSeparationApart) {
  // Three bumps on 100 x 50: heights 0.5 at (80, 10), 1 at (20, 30), 0.8 at (24, 33) (too near
  // the highest: within 0.1 x 100 = 10 px), and 0.3 at (60, 40).
  cv::Mat map(50, 100, CV_32FC1, cv::Scalar(0.f));
  map.at<float>(10, 80) = 0.5f;
  map.at<float>(30, 20) = 1.0f;
  map.at<float>(33, 24) = 0.8f;
  map.at<float>(40, 60) = 0.3f;
  const Scanpath peaks = SaliencyPeaks(map, {100, 50}, 3, 0.1, 0.2);
  ASSERT_EQ(peaks.size(), 3u);
  EXPECT_DOUBLE_EQ(peaks[0].x, 20.0);
  EXPECT_DOUBLE_EQ(peaks[0].y, 30.0);
  EXPECT_DOUBLE_EQ(peaks[1].x, 80.0);
  EXPECT_DOUBLE_EQ(peaks[2].x, 60.0);
  EXPECT_DOUBLE_EQ(peaks[2].y, 40.0);
  EXPECT_DOUBLE_EQ(peaks[2].duration_s, 0.2);
  // Without a separation the near bump counts: second highest.
  EXPECT_DOUBLE_EQ(SaliencyPeaks(map, {100, 50}, 2, 0.0, 0.2)[1].x, 24.0);
  // A map at half the image's size: its pixel centres scaled to the image's.
  cv::Mat half(25, 50, CV_32FC1, cv::Scalar(0.f));
  half.at<float>(15, 10) = 1.f;
  const Scanpath scaled = SaliencyPeaks(half, {100, 50}, 1, 0.1, 0.2);
  ASSERT_EQ(scaled.size(), 1u);
  EXPECT_DOUBLE_EQ(scaled[0].x, 20.5);
  EXPECT_DOUBLE_EQ(scaled[0].y, 30.5);
}

TEST(SaliencyPeaks, AFlatMapGivesPeaksSeparatedInRasterOrder) {
  const cv::Mat flat(50, 100, CV_32FC1, cv::Scalar(0.5f));
  const Scanpath peaks = SaliencyPeaks(flat, {100, 50}, 3, 0.1, 0.2);
  ASSERT_EQ(peaks.size(), 3u);
  EXPECT_DOUBLE_EQ(peaks[0].x, 0.0);
  EXPECT_DOUBLE_EQ(peaks[1].x, 11.0);
  EXPECT_DOUBLE_EQ(peaks[2].x, 22.0);
  for (const Fixation& f : peaks) EXPECT_DOUBLE_EQ(f.y, 0.0);
}

}  // namespace
}  // namespace attend
