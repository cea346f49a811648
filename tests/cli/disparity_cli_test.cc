// attend disparity end to end: the PFM it writes, its JSON report, the bad-pixel rates against
// ground truth in PFM and in scaled PNG, and the exit statuses of its errors (SPEC 3.2, 4).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

#include "io/pfm.h"
#include "stereo/disparity.h"
#include "tests/cli/attend_cli.h"
#include "tests/support/attend_process.h"
#include "tests/support/temp_dir.h"

namespace fs = std::filesystem;

namespace attend {
namespace {

using testing::Attend;
using testing::Contains;
using testing::ReadText;
using testing::Result;

// A random-dot pair 128x96: background at disparity 3, a 48x40 square at disparity 9.
constexpr int kWidth = 128;
constexpr int kHeight = 96;
constexpr int kBackground = 3;
constexpr int kForeground = 9;
const cv::Rect kSquare(44, 28, 48, 40);

// The left view's disparity of the pair: known everywhere except the left strip whose match
// would lie left of the right image (0, unknown).
cv::Mat TrueDisparity() {
  cv::Mat disparity(kHeight, kWidth, CV_32FC1, cv::Scalar(kBackground));
  disparity(kSquare).setTo(kForeground);
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      if (x - disparity.at<float>(y, x) < 0) disparity.at<float>(y, x) = 0.f;
    }
  }
  return disparity;
}

// Writes dir/left.png and dir/right.png: the right view is random dots, and every left pixel
// (x, y) with known disparity d copies the right pixel (x - d, y), so the map is exact.
void WritePair(const testing::TempDir& dir) {
  cv::RNG rng(20240612);
  cv::Mat right(kHeight, kWidth, CV_8UC1);
  rng.fill(right, cv::RNG::UNIFORM, 0, 256);
  cv::Mat left(kHeight, kWidth, CV_8UC1);
  rng.fill(left, cv::RNG::UNIFORM, 0, 256);
  const cv::Mat disparity = TrueDisparity();
  for (int y = 0; y < kHeight; ++y) {
    for (int x = 0; x < kWidth; ++x) {
      const int d = static_cast<int>(disparity.at<float>(y, x));
      if (d > 0) left.at<uchar>(y, x) = right.at<uchar>(y, x - d);
    }
  }
  ASSERT_TRUE(cv::imwrite(dir.File("left.png"), left));
  ASSERT_TRUE(cv::imwrite(dir.File("right.png"), right));
}

// The bad-pixel rates of SPEC 4, computed here independently of the estimator's library.
struct Rates {
  double bad1 = 0.0;
  double bad2 = 0.0;
  int known = 0;
};

Rates BadPixels(const cv::Mat& disparity, const cv::Mat& truth) {
  Rates rates;
  int bad1 = 0, bad2 = 0;
  for (int y = 0; y < truth.rows; ++y) {
    for (int x = 0; x < truth.cols; ++x) {
      const float t = truth.at<float>(y, x);
      if (!(t > 0.f) || !std::isfinite(t)) continue;
      ++rates.known;
      const float d = disparity.at<float>(y, x);
      const bool invalid = !std::isfinite(d) || d < 0.f;
      if (invalid || std::abs(d - t) > 1.f) ++bad1;
      if (invalid || std::abs(d - t) > 2.f) ++bad2;
    }
  }
  rates.bad1 = static_cast<double>(bad1) / rates.known;
  rates.bad2 = static_cast<double>(bad2) / rates.known;
  return rates;
}

nlohmann::json Json(const Result& r) {
  try {
    return nlohmann::json::parse(r.out);
  } catch (const nlohmann::json::exception& e) {
    ADD_FAILURE() << "stdout is not one JSON object: " << e.what() << "\n" << r.out;
    return {};
  }
}

// The names in the folder that look like temporary outputs.
std::vector<std::string> Leftovers(const testing::TempDir& dir) {
  std::vector<std::string> names;
  for (const auto& entry : fs::recursive_directory_iterator(dir.path())) {
    const std::string name = entry.path().filename().string();
    if (Contains(name, ".tmp")) names.push_back(name);
  }
  return names;
}

TEST(DisparityCommand, HelpNamesTheOptions) {
  testing::TempDir dir;
  const Result r = Attend(dir, {"disparity", "--help"});
  EXPECT_EQ(r.status, 0);
  for (const char* flag : {"--out", "--max-disparity", "--window", "--subpixel", "--lr-check",
                           "--gt", "--gt-scale", "--set"}) {
    EXPECT_TRUE(Contains(r.out, flag)) << flag << "\n" << r.out;
  }
}

TEST(DisparityCommand, WritesTheMapAndReportsItsAccuracy) {
  testing::TempDir dir;
  WritePair(dir);
  const cv::Mat truth = TrueDisparity();
  WritePfm(dir.File("truth.pfm"), truth);
  const Result r = Attend(dir, {"disparity", "left.png", "right.png", "--out", "out/map.pfm",
                                "--max-disparity", "16", "--gt", "truth.pfm"});
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json report = Json(r);
  EXPECT_EQ(report["left"], "left.png");
  EXPECT_EQ(report["right"], "right.png");
  EXPECT_EQ(report["out"], "out/map.pfm");
  EXPECT_EQ(report["width"], kWidth);
  EXPECT_EQ(report["height"], kHeight);
  EXPECT_GT(report["milliseconds"].get<double>(), 0.0);
  EXPECT_GT(report["buffer_bytes"].get<double>(), 0.0);
  EXPECT_EQ(report["options"]["max_disparity"], 16);
  EXPECT_EQ(report["options"]["window"], DisparityOptions{}.window);
  EXPECT_EQ(report["options"]["subpixel"], false);
  EXPECT_EQ(report["options"]["left_right_check"], DisparityOptions{}.left_right_check);
  EXPECT_EQ(report["options"]["lr_tolerance"], 1);
  EXPECT_EQ(report["options"]["smoothness"], "sgm");
  EXPECT_EQ(report["options"]["sgm_paths"], DisparityOptions{}.sgm_paths);
  EXPECT_EQ(report["options"]["median"], DisparityOptions{}.median);
  EXPECT_EQ(report["gt"], "truth.pfm");
  EXPECT_EQ(report["gt_scale"], 1.0);

  const cv::Mat map = ReadPfm(dir.File("out/map.pfm"));
  ASSERT_EQ(map.type(), CV_32FC1);
  ASSERT_EQ(map.size(), cv::Size(kWidth, kHeight));
  // The estimator recovers both planes away from the depth edges.
  EXPECT_NEAR(map.at<float>(kSquare.y + kSquare.height / 2, kSquare.x + kSquare.width / 2),
              kForeground, 0.5);
  EXPECT_NEAR(map.at<float>(10, kWidth - 20), kBackground, 0.5);
  EXPECT_NEAR(map.at<float>(kHeight - 10, 30), kBackground, 0.5);

  // The reported rates are those of the written map over the known pixels.
  const Rates expected = BadPixels(map, truth);
  EXPECT_EQ(report["known_pixels"], expected.known);
  EXPECT_EQ(expected.known, cv::countNonZero(truth));
  EXPECT_NEAR(report["bad1"].get<double>(), expected.bad1, 1e-12);
  EXPECT_NEAR(report["bad2"].get<double>(), expected.bad2, 1e-12);
  EXPECT_LT(expected.bad1, 0.08);
  EXPECT_LE(expected.bad2, expected.bad1);
  EXPECT_TRUE(Leftovers(dir).empty());
}

TEST(DisparityCommand, GroundTruthInScaledImages) {
  testing::TempDir dir;
  WritePair(dir);
  const cv::Mat truth = TrueDisparity();
  // Middlebury style: 8 bits holding disparity x 4 (PGM, as tsukuba and venus), and 16 bits
  // holding disparity x 256.
  cv::Mat times4, times256;
  truth.convertTo(times4, CV_8UC1, 4.0);
  truth.convertTo(times256, CV_16UC1, 256.0);
  ASSERT_TRUE(cv::imwrite(dir.File("truth4.pgm"), times4));
  ASSERT_TRUE(cv::imwrite(dir.File("truth256.png"), times256));

  const std::vector<std::string> pair = {"disparity", "left.png",        "right.png", "--out",
                                         "map.pfm",   "--max-disparity", "16"};
  const auto run = [&](const std::vector<std::string>& gt) {
    std::vector<std::string> args = pair;
    args.insert(args.end(), gt.begin(), gt.end());
    const Result r = Attend(dir, args);
    EXPECT_EQ(r.status, 0) << r.err;
    return Json(r);
  };
  for (const std::vector<std::string>& gt :
       {std::vector<std::string>{"--gt", "truth4.pgm", "--gt-scale", "4"},
        std::vector<std::string>{"--gt", "truth256.png", "--gt-scale", "256"}}) {
    const nlohmann::json report = run(gt);
    const Rates expected = BadPixels(ReadPfm(dir.File("map.pfm")), truth);
    EXPECT_EQ(report["known_pixels"], expected.known) << gt[1];
    EXPECT_NEAR(report["bad1"].get<double>(), expected.bad1, 1e-12) << gt[1];
    EXPECT_NEAR(report["bad2"].get<double>(), expected.bad2, 1e-12) << gt[1];
    EXPECT_LT(expected.bad1, 0.08) << gt[1];
    EXPECT_EQ(report["gt_scale"], std::stod(gt[3])) << gt[1];
  }
  // Without the scale the values are read as pixels, four times too far: nearly every pixel
  // is bad.
  const nlohmann::json unscaled = run({"--gt", "truth4.pgm"});
  EXPECT_EQ(unscaled["known_pixels"], cv::countNonZero(truth));
  EXPECT_GT(unscaled["bad2"].get<double>(), 0.9);
}

TEST(DisparityCommand, OptionsFromFlagsAndSet) {
  testing::TempDir dir;
  WritePair(dir);
  // An existing file is replaced.
  dir.Write("a.pfm", "previous");
  Result r = Attend(dir, {"disparity", "left.png", "right.png", "--out", "a.pfm", "--window", "7",
                          "--subpixel", "--lr-check", "--max-disparity", "12"});
  ASSERT_EQ(r.status, 0) << r.err;
  nlohmann::json report = Json(r);
  EXPECT_EQ(report["options"]["window"], 7);
  EXPECT_EQ(report["options"]["subpixel"], true);
  EXPECT_EQ(report["options"]["left_right_check"], true);
  EXPECT_EQ(report["options"]["max_disparity"], 12);
  EXPECT_FALSE(report.contains("bad1"));
  // Sub-pixel disparities are not all integers, and stay within the range searched.
  const cv::Mat subpixel = ReadPfm(dir.File("a.pfm"));
  int fractional = 0;
  for (int y = 0; y < subpixel.rows; ++y) {
    for (int x = 0; x < subpixel.cols; ++x) {
      const float d = subpixel.at<float>(y, x);
      EXPECT_GE(d, 0.f);
      EXPECT_LE(d, 11.5f);
      if (d != std::round(d)) ++fractional;
    }
  }
  EXPECT_GT(fractional, 0);

  r = Attend(
      dir, {"disparity", "left.png", "--set", "disparity.window=5", "right.png", "--out", "b.pfm",
            "--set", "disparity.subpixel=true", "--set", "disparity.left_right_check=true", "--set",
            "disparity.lr_tolerance=2", "--set", "disparity.max_disparity=14"});
  ASSERT_EQ(r.status, 0) << r.err;
  report = Json(r);
  EXPECT_EQ(report["options"]["window"], 5);
  EXPECT_EQ(report["options"]["subpixel"], true);
  EXPECT_EQ(report["options"]["left_right_check"], true);
  EXPECT_EQ(report["options"]["lr_tolerance"], 2);
  EXPECT_EQ(report["options"]["max_disparity"], 14);
}

TEST(DisparityCommand, KeepsAnExistingMapWhenItFails) {
  testing::TempDir dir;
  WritePair(dir);
  dir.Write("map.pfm", "previous");
  cv::imwrite(dir.File("small.png"), cv::Mat(20, 30, CV_8UC1, cv::Scalar(7)));
  const Result r =
      Attend(dir, {"disparity", "left.png", "right.png", "--out", "map.pfm", "--gt", "small.png"});
  EXPECT_EQ(r.status, 3);
  EXPECT_EQ(ReadText(dir.File("map.pfm")), "previous");
  EXPECT_TRUE(Leftovers(dir).empty());
}

TEST(DisparityCommand, BadInputExitsThreeNamingTheFileOrSizes) {
  testing::TempDir dir;
  WritePair(dir);
  dir.Write("text.png", "this is not a PNG");
  Result r = Attend(dir, {"disparity", "missing.png", "right.png", "--out", "m.pfm"});
  EXPECT_EQ(r.status, 3);
  EXPECT_TRUE(Contains(r.err, "attend: error: missing.png")) << r.err;

  r = Attend(dir, {"disparity", "left.png", "text.png", "--out", "m.pfm"});
  EXPECT_EQ(r.status, 3);
  EXPECT_TRUE(Contains(r.err, "attend: error: text.png")) << r.err;

  cv::imwrite(dir.File("wide.png"), cv::Mat(kHeight, kWidth + 2, CV_8UC3, cv::Scalar(1, 2, 3)));
  r = Attend(dir, {"disparity", "left.png", "wide.png", "--out", "m.pfm"});
  EXPECT_EQ(r.status, 3);
  EXPECT_TRUE(Contains(r.err, "128x96")) << r.err;
  EXPECT_TRUE(Contains(r.err, "130x96")) << r.err;

  // A range that is a valid option but does not fit these images.
  r = Attend(dir,
             {"disparity", "left.png", "right.png", "--out", "m.pfm", "--max-disparity", "128"});
  EXPECT_EQ(r.status, 3);
  EXPECT_TRUE(Contains(r.err, "128x96")) << r.err;
  EXPECT_TRUE(Contains(r.err, "max_disparity 128")) << r.err;

  cv::imwrite(dir.File("gt_small.png"), cv::Mat(kHeight - 1, kWidth, CV_8UC1, cv::Scalar(4)));
  r = Attend(dir, {"disparity", "left.png", "right.png", "--out", "m.pfm", "--gt", "gt_small.png",
                   "--gt-scale", "4"});
  EXPECT_EQ(r.status, 3);
  EXPECT_TRUE(Contains(r.err, "gt_small.png")) << r.err;
  EXPECT_TRUE(Contains(r.err, "128x95")) << r.err;

  cv::imwrite(dir.File("gt_colour.png"), cv::Mat(kHeight, kWidth, CV_8UC3, cv::Scalar(4, 4, 4)));
  r = Attend(dir,
             {"disparity", "left.png", "right.png", "--out", "m.pfm", "--gt", "gt_colour.png"});
  EXPECT_EQ(r.status, 3);
  EXPECT_TRUE(Contains(r.err, "gt_colour.png")) << r.err;

  EXPECT_FALSE(fs::exists(dir.File("m.pfm")));
  EXPECT_TRUE(Leftovers(dir).empty());
}

TEST(DisparityCommand, UsageConfigurationAndOutputErrorsExitTwo) {
  testing::TempDir dir;
  WritePair(dir);
  const std::vector<std::string> pair = {"disparity", "left.png", "right.png"};
  const auto run = [&](const std::vector<std::string>& more) {
    std::vector<std::string> args = pair;
    args.insert(args.end(), more.begin(), more.end());
    return Attend(dir, args);
  };
  Result r = run({});
  EXPECT_EQ(r.status, 2);
  EXPECT_TRUE(Contains(r.err, "--out")) << r.err;

  r = run({"--out", "m.pfm", "--window", "4"});
  EXPECT_EQ(r.status, 2);
  EXPECT_TRUE(Contains(r.err, "window")) << r.err;

  r = run({"--out", "m.pfm", "--gt-scale", "4"});
  EXPECT_EQ(r.status, 2);
  EXPECT_TRUE(Contains(r.err, "--gt")) << r.err;
  EXPECT_EQ(run({"--out", "m.pfm", "--gt", "left.png", "--gt-scale", "nan"}).status, 2);

  r = run({"--out", "m.pfm", "--set", "disparity.windw=5"});
  EXPECT_EQ(r.status, 2);
  EXPECT_TRUE(Contains(r.err, "windw")) << r.err;
  EXPECT_TRUE(Contains(r.err, "window")) << r.err;
  r = run({"--out", "m.pfm", "--set", "disparity.max_disparity=0"});
  EXPECT_EQ(r.status, 2);
  EXPECT_TRUE(Contains(r.err, "disparity.max_disparity")) << r.err;
  // One key set two ways is ambiguous.
  r = run({"--out", "m.pfm", "--window", "7", "--set", "disparity.window=5"});
  EXPECT_EQ(r.status, 2);
  EXPECT_TRUE(Contains(r.err, "--window")) << r.err;
  EXPECT_TRUE(Contains(r.err, "disparity.window=5")) << r.err;

  // Output that cannot be written: not a .pfm, a folder, below a regular file.
  EXPECT_EQ(run({"--out", "m.png"}).status, 2);
  fs::create_directories(dir.File("folder.pfm"));
  r = run({"--out", "folder.pfm", "--max-disparity", "16"});
  EXPECT_EQ(r.status, 2);
  EXPECT_TRUE(Contains(r.err, "folder.pfm")) << r.err;
  dir.Write("file", "not a folder");
  r = run({"--out", "file/m.pfm", "--max-disparity", "16"});
  EXPECT_EQ(r.status, 2);
  EXPECT_TRUE(Contains(r.err, "file")) << r.err;

  EXPECT_FALSE(fs::exists(dir.File("m.pfm")));
  EXPECT_FALSE(fs::exists(dir.File("m.png")));
  EXPECT_TRUE(Leftovers(dir).empty());
}

}  // namespace
}  // namespace attend
