// attend segment end to end: the files it writes, segment.json, and the exit statuses of its
// errors (SPEC 3.2).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <set>

#include "tests/cli/attend_cli.h"
#include "tests/support/attend_process.h"
#include "tests/support/temp_dir.h"

namespace fs = std::filesystem;

namespace attend {
namespace {

using testing::Contains;
using testing::ReadText;
using testing::Result;

using testing::Attend;

// The variant links the regular and irregular parts of the background, so that the four
// rectangles below are exactly five regions (tests/pyramid/segmentation_test.cc).
const char kVariant[] = "segmentation.link_across_kinds=true";

// Thesis figure 3.4a: four rectangles of different colours on a background, 128x128.
const std::vector<cv::Rect> kBoxes = {cv::Rect(10, 12, 30, 20), cv::Rect(61, 9, 41, 33),
                                      cv::Rect(17, 70, 23, 45), cv::Rect(69, 77, 50, 31)};
const std::vector<cv::Scalar> kBoxColours = {cv::Scalar(0, 0, 220), cv::Scalar(0, 200, 0),
                                             cv::Scalar(220, 0, 0), cv::Scalar(0, 220, 220)};

std::string WriteFourRectangles(const testing::TempDir& dir, const std::string& name) {
  cv::Mat image(128, 128, CV_8UC3, cv::Scalar(180, 180, 180));
  for (size_t i = 0; i < kBoxes.size(); ++i) {
    cv::rectangle(image, kBoxes[i], kBoxColours[i], cv::FILLED);
  }
  const std::string path = dir.File(name);
  EXPECT_TRUE(cv::imwrite(path, image)) << path;
  return path;
}

// An 8-bit grey image 64x48: left half 50, right half 200.
std::string WriteGreyHalves(const testing::TempDir& dir, const std::string& name) {
  cv::Mat image(48, 64, CV_8UC1, cv::Scalar(50));
  image.colRange(32, 64).setTo(200);
  const std::string path = dir.File(name);
  EXPECT_TRUE(cv::imwrite(path, image)) << path;
  return path;
}

int DistinctValues(const cv::Mat& labels16) {
  std::set<uint16_t> values;
  for (int row = 0; row < labels16.rows; ++row) {
    for (int col = 0; col < labels16.cols; ++col) values.insert(labels16.at<uint16_t>(row, col));
  }
  return static_cast<int>(values.size());
}

nlohmann::json ReadJson(const std::string& path) {
  const std::string text = ReadText(path);
  EXPECT_FALSE(text.empty()) << path;
  return nlohmann::json::parse(text);
}

TEST(SegmentCommand, HelpNamesTheFilesAndTheColourConversion) {
  testing::TempDir dir;
  const Result r = Attend(dir, {"segment", "--help"});
  EXPECT_EQ(r.status, 0);
  EXPECT_TRUE(Contains(r.out, "--metrics")) << r.out;
  EXPECT_TRUE(Contains(r.out, "labels.png")) << r.out;
  EXPECT_TRUE(Contains(r.out, "grey")) << r.out;
  EXPECT_TRUE(Contains(r.out, "16-bit images are scaled")) << r.out;
}

TEST(SegmentCommand, WritesLabelsFalseColourMeanAndReport) {
  testing::TempDir dir;
  const std::string rectangles = WriteFourRectangles(dir, "rects.png");
  const std::string grey = WriteGreyHalves(dir, "grey.png");
  // A non-empty --out is fine: other files stay.
  dir.Write("out/keep.txt", "mine");
  // An image after --set is an image, not a second value of --set.
  const Result r = Attend(dir, {"segment", rectangles, "--set", kVariant, grey, "--out", "out"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(ReadText(dir.File("out/keep.txt")), "mine");
  EXPECT_TRUE(Contains(r.out, "rects.png: 5 regions")) << r.out;
  EXPECT_TRUE(Contains(r.out, "grey.png: 2 regions")) << r.out;

  const cv::Mat labels = cv::imread(dir.File("out/rects.labels.png"), cv::IMREAD_UNCHANGED);
  ASSERT_FALSE(labels.empty());
  EXPECT_EQ(labels.type(), CV_16UC1);
  EXPECT_EQ(labels.size(), cv::Size(128, 128));
  EXPECT_EQ(DistinctValues(labels), 5);
  // Each rectangle is one label of its own.
  std::set<uint16_t> box_labels;
  for (const cv::Rect& box : kBoxes) {
    const uint16_t label = labels.at<uint16_t>(box.y + box.height / 2, box.x + box.width / 2);
    box_labels.insert(label);
    EXPECT_EQ(cv::countNonZero(labels(box) != label), 0) << box;
  }
  EXPECT_EQ(box_labels.size(), 4u);

  const cv::Mat grey_labels = cv::imread(dir.File("out/grey.labels.png"), cv::IMREAD_UNCHANGED);
  ASSERT_FALSE(grey_labels.empty());
  EXPECT_EQ(grey_labels.type(), CV_16UC1);
  EXPECT_EQ(DistinctValues(grey_labels), 2);

  const cv::Mat regions = cv::imread(dir.File("out/rects.regions.png"), cv::IMREAD_UNCHANGED);
  EXPECT_EQ(regions.type(), CV_8UC3);
  EXPECT_EQ(regions.size(), cv::Size(128, 128));
  const cv::Mat mean = cv::imread(dir.File("out/rects.mean.png"), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(mean.type(), CV_8UC3);
  // A constant rectangle's mean colour is its colour (up to the HSV round trip's rounding).
  for (size_t i = 0; i < kBoxes.size(); ++i) {
    const cv::Vec3b got = mean.at<cv::Vec3b>(kBoxes[i].y + 1, kBoxes[i].x + 1);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], kBoxColours[i][c], 1.0) << "box " << i;
  }
  EXPECT_TRUE(fs::exists(dir.File("out/grey.regions.png")));
  EXPECT_TRUE(fs::exists(dir.File("out/grey.mean.png")));

  const nlohmann::json report = ReadJson(dir.File("out/segment.json"));
  ASSERT_EQ(report["images"].size(), 2u);
  const nlohmann::json& first = report["images"][0];
  EXPECT_EQ(first["image"], rectangles);
  EXPECT_EQ(first["width"], 128);
  EXPECT_EQ(first["height"], 128);
  EXPECT_EQ(first["regions"], 5);
  EXPECT_GE(first["pyramid_levels"].get<int>(), 2);
  EXPECT_GE(first["milliseconds"].get<double>(), 0.0);
  EXPECT_FALSE(first.contains("f"));
  EXPECT_FALSE(first.contains("shift_variance"));
  const nlohmann::json& second = report["images"][1];
  EXPECT_EQ(second["image"], grey);
  EXPECT_EQ(second["width"], 64);
  EXPECT_EQ(second["height"], 48);
  EXPECT_EQ(second["regions"], 2);
  EXPECT_TRUE(second["milliseconds"].is_number());
  // configs/segment.yaml's values, with the --set of link_across_kinds.
  EXPECT_EQ(report["options"]["t_max"], 50.0);
  EXPECT_EQ(report["options"]["merge_spread"], 1.0);
  EXPECT_EQ(report["options"]["link_across_kinds"], true);
}

TEST(SegmentCommand, MetricsAddFQAndShiftVariance) {
  testing::TempDir dir;
  const std::string rectangles = WriteFourRectangles(dir, "rects.png");
  const std::string grey = WriteGreyHalves(dir, "grey.png");
  cv::imwrite(dir.File("tiny.png"), cv::Mat(16, 24, CV_8UC3, cv::Scalar(1, 2, 3)));
  const Result r = Attend(dir, {"segment", rectangles, grey, "tiny.png", "--out", "out",
                                "--metrics", "--quiet", "--set", kVariant});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out, "");  // --quiet

  const nlohmann::json report = ReadJson(dir.File("out/segment.json"));
  ASSERT_EQ(report["images"].size(), 3u);
  const nlohmann::json& first = report["images"][0];
  // A perfect segmentation of a piecewise-constant image: no colour error, and Q is its area
  // term alone, sqrt(5) / (10000 * 128 * 128) * sum 1 / A_i^2 (all areas differ).
  EXPECT_EQ(first["f"], 0.0);
  double area_term = 128.0 * 128.0;
  double sum = 0.0;
  for (const cv::Rect& box : kBoxes) {
    area_term -= box.area();
    sum += 1.0 / (static_cast<double>(box.area()) * box.area());
  }
  sum += 1.0 / (area_term * area_term);
  const double q = std::sqrt(5.0) / (1e4 * 128 * 128) * sum;
  EXPECT_NEAR(first["q"].get<double>() / q, 1.0, 1e-12) << first["q"] << " vs " << q;
  ASSERT_TRUE(first["shift_variance"].is_number()) << first;
  EXPECT_GE(first["shift_variance"].get<double>(), 0.0);
  const nlohmann::json& second = report["images"][1];
  EXPECT_TRUE(second["f"].is_number());
  EXPECT_TRUE(second["q"].is_number());
  EXPECT_TRUE(second["shift_variance"].is_number());
  // 16 pixels high: too small for a window wider than the 10-pixel shift.
  const nlohmann::json& tiny = report["images"][2];
  EXPECT_TRUE(tiny["f"].is_number());
  EXPECT_TRUE(tiny["shift_variance"].is_null()) << tiny;
  EXPECT_TRUE(Contains(tiny["shift_variance_note"].get<std::string>(), "24x16")) << tiny;
}

// The signature and IHDR chunk of an 8-bit RGB PNG of the given size, and nothing else.
std::string HugePngHeader(uint32_t width, uint32_t height) {
  auto be32 = [](uint32_t v) {
    return std::string{static_cast<char>(v >> 24), static_cast<char>(v >> 16),
                       static_cast<char>(v >> 8), static_cast<char>(v)};
  };
  const std::string chunk = "IHDR" + be32(width) + be32(height) + std::string("\x08\x02\0\0\0", 5);
  uint32_t crc = 0xffffffffu;  // CRC-32 of the chunk type and data, as PNG requires
  for (unsigned char byte : chunk) {
    crc ^= byte;
    for (int bit = 0; bit < 8; ++bit) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
  }
  // A tiny IDAT and the IEND chunk (fixed bytes): with them OpenCV reads the header and stops
  // at its pixel limit rather than at a missing chunk.
  const std::string tail(
      "\x00\x00\x00\x0c"
      "IDAT"
      "\x78\x9c\x63\x60\xa0\x3d\x00\x00\x00\x64\x00\x01"
      "\x86\x64\x3c\x35"
      "\x00\x00\x00\x00"
      "IEND"
      "\xae\x42\x60\x82",
      36);
  return std::string("\x89PNG\r\n\x1a\n", 8) + be32(13) + chunk + be32(~crc) + tail;
}

TEST(SegmentCommand, UnreadableImagesExitThreeNamingThePath) {
  testing::TempDir dir;
  const std::string good = WriteFourRectangles(dir, "rects.png");
  dir.Write("text.png", "this is not a PNG");
  Result r = Attend(dir, {"segment", good, "text.png", "--out", "out"});
  EXPECT_EQ(r.status, 3);
  EXPECT_TRUE(Contains(r.err, "attend: error: text.png")) << r.err;

  dir.Write("empty.png", "");
  r = Attend(dir, {"segment", "empty.png", "--out", "out"});
  EXPECT_EQ(r.status, 3);
  EXPECT_TRUE(Contains(r.err, "attend: error: empty.png")) << r.err;

  r = Attend(dir, {"segment", "missing.png", "--out", "out"});
  EXPECT_EQ(r.status, 3);
  EXPECT_TRUE(Contains(r.err, "attend: error: missing.png")) << r.err;

  // A PNG whose header claims 100000 x 100000 pixels: OpenCV refuses it by throwing, which must
  // come out as bad input, not as an internal error.
  dir.Write("huge.png", HugePngHeader(100000, 100000));
  r = Attend(dir, {"segment", "huge.png", "--out", "out"});
  EXPECT_EQ(r.status, 3) << r.err;
  EXPECT_TRUE(Contains(r.err, "attend: error: huge.png: cannot be decoded")) << r.err;
}

TEST(SegmentCommand, UsageAndConfigurationErrorsExitTwo) {
  testing::TempDir dir;
  const std::string good = WriteFourRectangles(dir, "rects.png");
  Result r = Attend(dir, {"segment", good});
  EXPECT_EQ(r.status, 2);
  EXPECT_TRUE(Contains(r.err, "--out")) << r.err;

  r = Attend(dir, {"segment", "--out", "out"});
  EXPECT_EQ(r.status, 2);
  EXPECT_TRUE(Contains(r.err, "IMAGE")) << r.err;

  r = Attend(dir, {"segment", good, "--out", "out", "--set", "segmentation.t_max=-1"});
  EXPECT_EQ(r.status, 2);
  EXPECT_TRUE(Contains(r.err, "segmentation.t_max")) << r.err;

  r = Attend(dir, {"segment", good, "--out", "out", "--no-such-flag"});
  EXPECT_EQ(r.status, 2);

  fs::create_directories(dir.File("a"));
  fs::create_directories(dir.File("b"));
  const std::string a = WriteFourRectangles(dir, "a/same.png");
  const std::string b = WriteGreyHalves(dir, "b/same.png");
  r = Attend(dir, {"segment", a, b, "--out", "out"});
  EXPECT_EQ(r.status, 2);
  EXPECT_TRUE(Contains(r.err, a)) << r.err;
  EXPECT_TRUE(Contains(r.err, b)) << r.err;
  EXPECT_FALSE(fs::exists(dir.File("out/same.labels.png")));
}

}  // namespace
}  // namespace attend
