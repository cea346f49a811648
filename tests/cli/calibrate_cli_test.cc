// attend calibrate end to end (docs/STEREO3D.md): opencv-doc's chessboard pairs (skipped
// without them), the conversions of KITTI's and EuRoC's projections, a run through the written
// calibration, and the exit statuses of its errors.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

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

const char kOpenCvData[] = "/usr/share/doc/opencv-doc/examples/data";

// SEQ/left and SEQ/right holding opencv-doc's 13 chessboard pairs (links), or "" when the
// package is not installed.
std::string ChessboardPairs(const testing::TempDir& dir) {
  if (!fs::exists(fs::path(kOpenCvData) / "left01.jpg")) return "";
  const fs::path seq = dir.path() / "pairs";
  fs::create_directories(seq / "left");
  fs::create_directories(seq / "right");
  for (const fs::directory_entry& entry : fs::directory_iterator(kOpenCvData)) {
    const std::string name = entry.path().filename().string();
    for (const char* view : {"left", "right"}) {
      const std::string prefix = view;
      if (name.size() == prefix.size() + 6 && name.rfind(prefix, 0) == 0 &&
          entry.path().extension() == ".jpg") {
        fs::create_symlink(entry.path(), seq / view / name);
      }
    }
  }
  return seq.string();
}

TEST(CalibrateCli, OpenCvDocPairsGiveSubPixelRmsAndRectifiedRows) {
  const testing::TempDir dir;
  const std::string pairs = ChessboardPairs(dir);
  if (pairs.empty()) {
    GTEST_SKIP() << kOpenCvData << "/left01.jpg is absent: install Debian's opencv-doc "
                 << "(scripts/install_deps.sh) for the chessboard pairs";
  }
  const Result r = Attend(dir, {"calibrate", "--left", pairs + "/left", "--right",
                                pairs + "/right", "--board", "9x6", "--square", "0.025", "--out",
                                dir.File("calib.yaml")});
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json json = nlohmann::json::parse(r.out);
  EXPECT_EQ(json["pairs"], 13);
  EXPECT_GE(json["pairs_used"].get<int>(), 10);
  EXPECT_LT(json["rms_px"].get<double>(), 0.5);
  EXPECT_LT(json["rectified_row_offset_px"].get<double>(), 1.0);
  EXPECT_LT(json["corner_row_error_px"].get<double>(), 1.0);
  EXPECT_EQ(json["skipped"].size(), 13u - json["pairs_used"].get<size_t>());
  EXPECT_TRUE(fs::exists(dir.File("calib.yaml")));

  // A run on the raw pairs through the calibration reads rectified rows.
  const Result run = Attend(dir, {"run", "--sequence", pairs, "--calib", dir.File("calib.yaml"),
                                  "--frames", "0:1", "--out", dir.File("run"), "--quiet"});
  ASSERT_EQ(run.status, 0) << run.err;
  const nlohmann::json summary = nlohmann::json::parse(ReadText(dir.File("run/summary.json")));
  EXPECT_EQ(summary["stereo"]["calibration"]["form"], "full");
  EXPECT_EQ(summary["stereo"]["rectified_on_the_fly"], true);
  if (summary["stereo"]["matches"].get<int>() >= 20) {
    EXPECT_LT(summary["stereo"]["row_offset_px"].get<double>(), 1.0);
  }
}

TEST(CalibrateCli, BadFlagsExitWithStatus2) {
  const testing::TempDir dir;
  fs::create_directories(dir.path() / "l");
  fs::create_directories(dir.path() / "r");
  const std::vector<std::string> base = {"calibrate", "--left", dir.File("l"), "--right",
                                         dir.File("r"), "--out", dir.File("c.yaml")};
  auto with = [&](std::vector<std::string> extra) {
    std::vector<std::string> args = base;
    args.insert(args.end(), extra.begin(), extra.end());
    return Attend(dir, args);
  };
  Result r = with({"--board", "9", "--square", "0.025"});
  EXPECT_EQ(r.status, 2);
  EXPECT_TRUE(Contains(r.err, "--board")) << r.err;
  r = with({"--board", "9x6", "--square", "-1"});
  EXPECT_EQ(r.status, 2);
  EXPECT_TRUE(Contains(r.err, "--square")) << r.err;
  r = with({"--board", "9x6", "--square", "0.025", "--unknown"});
  EXPECT_EQ(r.status, 2);
  r = Attend(dir, {"calibrate", "--board", "9x6", "--square", "0.02", "--out", "c.yaml"});
  EXPECT_EQ(r.status, 2);
  EXPECT_TRUE(Contains(r.err, "--left")) << r.err;
  EXPECT_EQ(Attend(dir, {"calibrate", "--help"}).status, 0);
}

TEST(CalibrateCli, NoPairsOrTooFewBoardsExitWithStatus3NamingTheFiles) {
  const testing::TempDir dir;
  fs::create_directories(dir.path() / "l");
  fs::create_directories(dir.path() / "r");
  const std::vector<std::string> args = {"calibrate", "--left", dir.File("l"), "--right",
                                         dir.File("r"), "--board", "9x6", "--square", "0.025",
                                         "--out", dir.File("c.yaml")};
  Result r = Attend(dir, args);
  EXPECT_EQ(r.status, 3);
  EXPECT_TRUE(Contains(r.err, "no pairs")) << r.err;
  const cv::Mat blank(120, 160, CV_8UC3, cv::Scalar(128, 128, 128));
  cv::imwrite(dir.File("l/a.png"), blank);
  cv::imwrite(dir.File("r/a.png"), blank);
  r = Attend(dir, args);
  EXPECT_EQ(r.status, 3);
  EXPECT_TRUE(Contains(r.err, dir.File("l/a.png"))) << r.err;
  EXPECT_TRUE(Contains(r.err, "no 9x6 board found")) << r.err;
  EXPECT_FALSE(fs::exists(dir.File("c.yaml")));
}

TEST(CalibrateCli, ConvertsEurocAndKittiProjections) {
  const testing::TempDir dir;
  // A calib.txt in EuRoC's layout (the shared data's), with numbers of this test's own.
  dir.Write("euroc.txt",
            "# rectified\n"
            "P_left: 400 0 320 0 0 400 240 0 0 0 1 0\n"
            "P_right: 400 0 320 -40 0 400 240 0 0 0 1 0\n"
            "width: 640\nheight: 480\n");
  Result r = Attend(dir, {"calibrate", "--from-euroc", dir.File("euroc.txt"), "--out",
                          dir.File("euroc.yaml")});
  ASSERT_EQ(r.status, 0) << r.err;
  nlohmann::json json = nlohmann::json::parse(r.out);
  EXPECT_DOUBLE_EQ(json["focal_px"].get<double>(), 400.0);
  EXPECT_DOUBLE_EQ(json["baseline_m"].get<double>(), 0.1);
  EXPECT_EQ(json["image_size"], nlohmann::json::array({640, 480}));
  // KITTI's raw set: both projections in camera 0's rectified frame.
  dir.Write("kitti.txt",
            "calib_time: 09-Jan-2012 13:57:47\n"
            "S_rect_02: 1.242000e+03 3.750000e+02\n"
            "P_rect_02: 700 0 600 42 0 700 170 0.2 0 0 1 0.003\n"
            "P_rect_03: 700 0 600 -336 0 700 170 2.2 0 0 1 0.003\n");
  r = Attend(dir, {"calibrate", "--from-kitti", dir.File("kitti.txt"), "--out",
                   dir.File("kitti.yaml")});
  ASSERT_EQ(r.status, 0) << r.err;
  json = nlohmann::json::parse(r.out);
  EXPECT_NEAR(json["baseline_m"].get<double>(), 0.54, 1e-12);
  EXPECT_EQ(json["image_size"], nlohmann::json::array({1242, 375}));
  // The odometry set's calib.txt has no size.
  dir.Write("odometry.txt", "P2: 700 0 600 42 0 700 170 0.2 0 0 1 0.003\n"
                            "P3: 700 0 600 -336 0 700 170 2.2 0 0 1 0.003\n");
  r = Attend(dir, {"calibrate", "--from-kitti", dir.File("odometry.txt"), "--out",
                   dir.File("o.yaml")});
  EXPECT_EQ(r.status, 3);
  EXPECT_TRUE(Contains(r.err, "--size")) << r.err;
  r = Attend(dir, {"calibrate", "--from-kitti", dir.File("odometry.txt"), "--size", "1241x376",
                   "--out", dir.File("o.yaml")});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["image_size"], nlohmann::json::array({1241, 376}));
  dir.Write("broken.txt", "P_left: 400 0 320 0 0 400 240 0 0 0 1\nwidth: 640\nheight: 480\n");
  r = Attend(dir, {"calibrate", "--from-euroc", dir.File("broken.txt"), "--out",
                   dir.File("b.yaml")});
  EXPECT_EQ(r.status, 3);
  EXPECT_TRUE(Contains(r.err, "P_left must hold 12 numbers")) << r.err;
  // An output that cannot be written: OutputError.
  r = Attend(dir, {"calibrate", "--from-euroc", dir.File("euroc.txt"), "--out",
                   dir.File("no/such/folder/c.yaml")});
  EXPECT_EQ(r.status, 2);
  EXPECT_TRUE(Contains(r.err, "cannot write the calibration")) << r.err;
}

// The shared data's EuRoC calib.txt: its focal length and baseline come back.
TEST(CalibrateCli, EurocCalibTxtOfTheSharedData) {
  const std::string calib = testing::SharedData() + "/euroc_v1_01/calib.txt";
  if (!fs::exists(calib)) GTEST_SKIP() << calib << " is absent (the reference data)";
  const testing::TempDir dir;
  const Result r = Attend(dir, {"calibrate", "--from-euroc", calib, "--out", dir.File("c.yaml")});
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json json = nlohmann::json::parse(r.out);
  EXPECT_NEAR(json["focal_px"].get<double>(), 436.23, 0.005);
  EXPECT_NEAR(json["baseline_m"].get<double>(), 0.110, 0.0005);
  EXPECT_EQ(json["image_size"], nlohmann::json::array({752, 480}));
}

TEST(CalibrateCli, RunRefusesACalibWithAMonocularSource) {
  const testing::TempDir dir;
  fs::create_directories(dir.path() / "mono");
  cv::imwrite(dir.File("mono/0.png"), cv::Mat(48, 64, CV_8UC3, cv::Scalar(10, 20, 30)));
  dir.Write("euroc.txt", "P_left: 60 0 32 0 0 60 24 0 0 0 1 0\n"
                         "P_right: 60 0 32 -6 0 60 24 0 0 0 1 0\nwidth: 64\nheight: 48\n");
  ASSERT_EQ(Attend(dir, {"calibrate", "--from-euroc", dir.File("euroc.txt"), "--out",
                         dir.File("c.yaml")})
                .status,
            0);
  const Result r = Attend(dir, {"run", "--images", dir.File("mono"), "--calib", dir.File("c.yaml"),
                                "--out", dir.File("run"), "--quiet"});
  EXPECT_EQ(r.status, 2);
  EXPECT_TRUE(Contains(r.err, "monocular")) << r.err;
}

}  // namespace
}  // namespace attend
