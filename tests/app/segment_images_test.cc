#include "app/segment_images.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "tests/support/temp_dir.h"
#include "util/error.h"

namespace attend {
namespace {

namespace fs = std::filesystem;

// Three flat rectangles on a flat background: at least four regions.
cv::Mat FourRegions() {
  cv::Mat image(60, 80, CV_8UC3, cv::Scalar(200, 200, 200));
  cv::rectangle(image, cv::Rect(5, 5, 20, 20), cv::Scalar(20, 20, 220), cv::FILLED);
  cv::rectangle(image, cv::Rect(40, 8, 25, 15), cv::Scalar(220, 30, 30), cv::FILLED);
  cv::rectangle(image, cv::Rect(20, 35, 40, 18), cv::Scalar(30, 180, 30), cv::FILLED);
  return image;
}

TEST(SegmentImages, WritesEachImagesFilesAndReportsEveryImageInOrder) {
  testing::TempDir dir;
  ASSERT_TRUE(cv::imwrite(dir.File("a.png"), FourRegions()));
  ASSERT_TRUE(cv::imwrite(dir.File("b.png"), cv::Mat(30, 40, CV_8UC3, cv::Scalar(9, 90, 200))));
  SegmentRequest request;
  request.images = {dir.File("a.png"), dir.File("b.png")};
  request.stems = {"a", "b"};
  request.out = dir.File("out/nested");
  std::vector<SegmentedImage> heard;
  SegmentImages(request, [&](const SegmentedImage& image) { heard.push_back(image); });

  // What the segmenter gives the image on its own; one region for the flat image.
  Segmentation expected;
  Segmenter(request.options).Segment(FourRegions(), &expected);
  ASSERT_EQ(heard.size(), 2u);
  EXPECT_EQ(heard[0].path, dir.File("a.png"));
  EXPECT_EQ(heard[0].regions, expected.regions.size());
  EXPECT_GE(heard[0].regions, 4u);
  EXPECT_EQ(heard[0].size, cv::Size(80, 60));
  EXPECT_EQ(heard[1].regions, 1u);
  EXPECT_FALSE(heard[0].quality.has_value());
  // The labels file holds the segmentation's labels, as 16 bits.
  const cv::Mat labels = cv::imread(dir.File("out/nested/a.labels.png"), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(labels.type(), CV_16UC1);
  cv::Mat expected16;
  expected.labels.convertTo(expected16, CV_16UC1);
  EXPECT_EQ(cv::norm(labels, expected16, cv::NORM_INF), 0.0);
  for (const char* name : {"a.regions.png", "a.mean.png", "b.labels.png", "segment.json"}) {
    EXPECT_TRUE(fs::exists(dir.File(std::string("out/nested/") + name))) << name;
  }
  std::ifstream report(dir.File("out/nested/segment.json"));
  const nlohmann::json json = nlohmann::json::parse(report);
  EXPECT_EQ(json["images"].size(), 2u);
  EXPECT_EQ(json["images"][0]["regions"], expected.regions.size());
}

TEST(SegmentImages, MetricsComeWithTheImageAndAMissingImageKeepsTheFilesDone) {
  testing::TempDir dir;
  ASSERT_TRUE(cv::imwrite(dir.File("a.png"), FourRegions()));
  SegmentRequest request;
  request.images = {dir.File("a.png"), dir.File("missing.png")};
  request.stems = {"a", "missing"};
  request.out = dir.File("out");
  request.metrics = true;
  std::vector<SegmentedImage> heard;
  try {
    SegmentImages(request, [&](const SegmentedImage& image) { heard.push_back(image); });
    FAIL() << "a missing image is an input error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), dir.File("missing.png") + ": no such image file");
  }
  ASSERT_EQ(heard.size(), 1u);
  ASSERT_TRUE(heard[0].quality.has_value());
  ASSERT_TRUE(heard[0].shift_variance.has_value());  // 60 x 80 leaves a 50-pixel window
  EXPECT_TRUE(fs::exists(dir.File("out/a.labels.png")));
  EXPECT_FALSE(fs::exists(dir.File("out/segment.json")));
}

}  // namespace
}  // namespace attend
