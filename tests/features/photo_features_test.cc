// The still-photograph features (docs/FIXATIONS.md): centre_bias and centre_surround, on inputs whose
// answer is known by construction.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "features/centre_bias.h"
#include "features/centre_surround.h"

namespace attend {
namespace {

TEST(CentreBias, PeaksAtTheCentreAndFallsByTheGaussianOfItsSigma) {
  cv::Mat map;
  CentreBiasMap({101, 51}, 0.25, &map);
  ASSERT_EQ(map.size(), cv::Size(101, 51));
  EXPECT_FLOAT_EQ(map.at<float>(25, 50), 1.f);
  // One sigma (0.25 x 101 px) right of the centre: exp(-1/2).
  const int x = 50 + static_cast<int>(std::lround(0.25 * 101));
  EXPECT_NEAR(map.at<float>(25, x), std::exp(-0.5 * std::pow((x - 50) / (0.25 * 101), 2)), 1e-5);
  // Symmetric, and anisotropic: the vertical sigma is a share of the height.
  EXPECT_FLOAT_EQ(map.at<float>(10, 50), map.at<float>(40, 50));
  EXPECT_NEAR(map.at<float>(25 - 13, 50), std::exp(-0.5 * std::pow(13 / (0.25 * 51), 2)), 1e-5);
}

TEST(CentreSurround, ASmallObjectThatDiffersInColourOnlyStandsOut) {
  // An isoluminant-ish green square on grey: the a/b channels carry it.
  cv::Mat image(120, 160, CV_8UC3, cv::Scalar(128, 128, 128));
  const cv::Rect object(100, 30, 10, 10);
  image(object).setTo(cv::Scalar(80, 150, 80));
  cv::Mat map;
  CentreSurroundMap(image, CentreSurroundOptions{}, &map);
  ASSERT_EQ(map.type(), CV_32FC1);
  double high = 0.0;
  cv::Point at;
  cv::minMaxLoc(map, nullptr, &high, nullptr, &at);
  EXPECT_FLOAT_EQ(static_cast<float>(high), 1.f);
  const cv::Rect near(object.x - 3, object.y - 3, object.width + 6, object.height + 6);
  EXPECT_TRUE(near.contains(at)) << at;
  // Far from the object the map is flat and low.
  EXPECT_LT(map.at<float>(100, 20), 0.05f);
}

TEST(CentreSurround, AUniformImageGivesZero) {
  cv::Mat map;
  CentreSurroundMap(cv::Mat(40, 50, CV_8UC3, cv::Scalar(10, 200, 30)), CentreSurroundOptions{},
                    &map);
  EXPECT_EQ(cv::countNonZero(map > 1e-6f), 0);
}

TEST(CentreSurround, OptionsAreChecked) {
  CentreSurroundOptions options;
  options.scales = {};
  EXPECT_NE(options.Check().find("scales"), std::string::npos);
  options.scales = {2.0};
  options.surround = 1.0;
  EXPECT_NE(options.Check().find("surround"), std::string::npos);
}

}  // namespace
}  // namespace attend
