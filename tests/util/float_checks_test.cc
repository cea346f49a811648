#include "util/float_checks.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace attend {
namespace {

TEST(FloatChecks, EveryValueInRange) {
  cv::Mat map(7, 13, CV_32FC1);
  cv::randu(map, 0.0, 1.0);
  map.at<float>(0, 0) = 0.f;
  map.at<float>(6, 12) = 1.f;
  EXPECT_TRUE(AllFloatsWithin(map, 0.f, 1.f));  // both ends belong to the range
  EXPECT_TRUE(AllFloatsFinite(map));
  EXPECT_TRUE(AllFloatsWithin(cv::Mat(), 0.f, 1.f));
}

TEST(FloatChecks, OneValueOutsideAnywhereIsFound) {
  const float bad[] = {-1e-7f, std::nextafter(1.f, 2.f), std::numeric_limits<float>::quiet_NaN(),
                       std::numeric_limits<float>::infinity()};
  // Every position, so that the vector loop's body and its remainder are both covered.
  for (const float value : bad) {
    for (int at = 0; at < 3 * 37; ++at) {
      cv::Mat map(3, 37, CV_32FC1, cv::Scalar(0.5f));
      map.at<float>(at / 37, at % 37) = value;
      EXPECT_FALSE(AllFloatsWithin(map, 0.f, 1.f)) << value << " at " << at;
    }
  }
  cv::Mat map(3, 37, CV_32FC1, cv::Scalar(1e30f));
  EXPECT_TRUE(AllFloatsFinite(map));
  map.at<float>(2, 36) = -std::numeric_limits<float>::infinity();
  EXPECT_FALSE(AllFloatsFinite(map));
  map.at<float>(2, 36) = std::numeric_limits<float>::quiet_NaN();
  EXPECT_FALSE(AllFloatsFinite(map));
}

TEST(FloatChecks, ViewsAndChannels) {
  // A view into a larger matrix: only its own values count.
  cv::Mat big(10, 10, CV_32FC1, cv::Scalar(5.f));
  cv::Mat view = big(cv::Rect(2, 2, 4, 4));
  view.setTo(0.25f);
  EXPECT_TRUE(AllFloatsWithin(view, 0.f, 1.f));
  view.at<float>(3, 3) = 2.f;
  EXPECT_FALSE(AllFloatsWithin(view, 0.f, 1.f));
  cv::Mat three(4, 4, CV_32FC3, cv::Scalar(0.1f, 0.2f, 0.3f));
  EXPECT_TRUE(AllFloatsWithin(three, 0.f, 1.f));
  three.at<cv::Vec3f>(3, 3)[2] = -1.f;
  EXPECT_FALSE(AllFloatsWithin(three, 0.f, 1.f));
}

}  // namespace
}  // namespace attend
