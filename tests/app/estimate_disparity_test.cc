#include "app/estimate_disparity.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <opencv2/imgcodecs.hpp>

#include "io/pfm.h"
#include "tests/support/temp_dir.h"
#include "util/error.h"

namespace attend {
namespace {

namespace fs = std::filesystem;

// A random texture and the same texture moved 5 pixels to the left: disparity 5 everywhere a
// left pixel has its match.
void WritePair(const testing::TempDir& dir, cv::Size right_size = cv::Size(96, 48)) {
  cv::RNG rng(3);
  cv::Mat texture(48, 101, CV_8UC1);
  rng.fill(texture, cv::RNG::UNIFORM, 0, 256);
  ASSERT_TRUE(cv::imwrite(dir.File("left.png"), texture(cv::Rect(0, 0, 96, 48))));
  ASSERT_TRUE(cv::imwrite(dir.File("right.png"),
                          texture(cv::Rect(5, 0, right_size.width, right_size.height))));
}

DisparityRequest Request(const testing::TempDir& dir) {
  DisparityRequest request;
  request.left = dir.File("left.png");
  request.right = dir.File("right.png");
  request.out = dir.File("maps/d.pfm");
  request.options.max_disparity = 16;
  return request;
}

TEST(EstimateDisparity, WritesTheEstimatorsMapAndScoresItAgainstGroundTruth) {
  testing::TempDir dir;
  WritePair(dir);
  // Ground truth 5 x 4 as an 8-bit image with --gt-scale 4; unknown (0) within 8 pixels of
  // the edges, where windows and the left border have no match.
  cv::Mat truth(48, 96, CV_8UC1, cv::Scalar(0));
  truth(cv::Rect(8, 8, 80, 32)).setTo(20);
  ASSERT_TRUE(cv::imwrite(dir.File("gt.png"), truth));
  DisparityRequest request = Request(dir);
  request.gt = dir.File("gt.png");
  request.gt_scale = 4.0;
  const nlohmann::json report = EstimateDisparity(request);

  cv::Mat expected;
  DisparityEstimator(request.options)
      .Compute(cv::imread(request.left, cv::IMREAD_GRAYSCALE),
               cv::imread(request.right, cv::IMREAD_GRAYSCALE), &expected);
  const cv::Mat written = ReadPfm(request.out);
  EXPECT_EQ(cv::norm(written, expected, cv::NORM_INF), 0.0);
  EXPECT_EQ(report["width"], 96);
  EXPECT_EQ(report["options"]["max_disparity"], 16);
  EXPECT_EQ(report["known_pixels"], 80 * 32);
  EXPECT_EQ(report["bad1"], 0.0);
}

TEST(EstimateDisparity, APairOfTwoSizesIsAnInputErrorAndWritesNothing) {
  testing::TempDir dir;
  WritePair(dir, cv::Size(90, 48));
  try {
    EstimateDisparity(Request(dir));
    FAIL() << "a pair of two sizes is an input error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("a stereo pair must have one size"), std::string::npos);
  }
  EXPECT_FALSE(fs::exists(dir.File("maps")));
}

}  // namespace
}  // namespace attend
