// KITTI's own layouts end to end (docs/SEQUENCES.md): `attend run --sequence` on a raw drive
// and on a tracking sequence (frames of a rendered scene in KITTI's folders, with KITTI
// calibration files of the scene's rig) records positions with KITTI's calibration, `attend
// eval` and `attend compare` score the runs against the sequences' labels (and LiDAR), and
// malformed files exit 3 naming the file and line.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "tests/cli/attend_cli.h"
#include "tests/support/attend_process.h"
#include "tests/support/kitti_maker.h"
#include "tests/support/temp_dir.h"

namespace attend {
namespace {

namespace fs = std::filesystem;
using testing::Attend;
using testing::Contains;
using testing::ReadText;
using testing::Result;

// The lab scene's rig (sequences/lab.yaml: 320x240, focal 300 px, baseline 0.12 m, the
// principal point at the centre, as synth's calib.yaml has it).
const testing::KittiTestRig kLabRig{300.0, 159.5, 119.5, 0.12, {320, 240}};

std::vector<cv::Mat> ReadView(const testing::TempDir& dir, const std::string& view, int count) {
  std::vector<cv::Mat> frames;
  for (int i = 0; i < count; ++i) {
    char name[32];
    std::snprintf(name, sizeof(name), "/%06d.png", i);
    frames.push_back(cv::imread(dir.File("seq/" + view + name)));
  }
  return frames;
}

// Runs attend on `folder` and checks that the targets' positions come from the lab rig's
// calibration: Z times the disparity is focal times baseline, 36 px m.
void ExpectRunWithPositions(const testing::TempDir& dir, const std::string& folder,
                            const std::string& run, const std::string& calibration_file) {
  Result r = Attend(
      dir, {"run", "--sequence", folder, "--out", run, "--quiet", "--set", "output.dump=[]"});
  ASSERT_EQ(r.status, 0) << r.err;
  int positions = 0;
  std::istringstream lines(ReadText(dir.File(run + "/frames.jsonl")));
  for (std::string line; std::getline(lines, line);) {
    const nlohmann::json record = nlohmann::json::parse(line);
    for (const nlohmann::json& t : record["targets"]) {
      if (!t.contains("position_m") || !t.contains("disparity_px")) continue;
      ++positions;
      EXPECT_NEAR(t["position_m"][2].get<double>() * t["disparity_px"].get<double>(), 36.0, 0.01)
          << t.dump();
    }
  }
  EXPECT_GT(positions, 0);
  const nlohmann::json summary = nlohmann::json::parse(ReadText(dir.File(run + "/summary.json")));
  EXPECT_TRUE(Contains(summary.dump(), calibration_file)) << summary.dump();
}

// attend eval on `run`: the sequence's labels as ground truth and the LiDAR block.
void ExpectEvalWithKittiTruth(const testing::TempDir& dir, const std::string& run,
                              const std::string& labels) {
  Result r = Attend(dir, {"eval", run});
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json report = nlohmann::json::parse(r.out);
  EXPECT_TRUE(Contains(report["gt"].get<std::string>(), labels)) << report.dump();
  EXPECT_EQ(report["objects"].get<int>(), 1) << report.dump();
  ASSERT_TRUE(report.contains("depth_lidar")) << report.dump();
  EXPECT_EQ(report["depth_lidar"]["min_points"].get<int>(), 3);
  // The flat ground and the car's rear of the scans lie in the inner half of the lab's targets.
  EXPECT_GT(report["depth_lidar"]["count"].get<int>(), 0) << report["depth_lidar"].dump();
}

TEST(KittiCli, RunsAndScoresARawDriveAndATrackingSequence) {
  const testing::TempDir dir;
  Result r = Attend(dir, {"synth", testing::ProjectRoot() + "/sequences/lab.yaml", "--out", "seq",
                          "--frames", "4"});
  ASSERT_EQ(r.status, 0) << r.err;
  const std::vector<cv::Mat> left = ReadView(dir, "left", 4), right = ReadView(dir, "right", 4);
  const std::string drive = testing::WriteKittiRawDrive(dir, kLabRig, left, right);
  const std::string tracking = testing::WriteKittiTracking(dir, kLabRig, left, right);
  ExpectRunWithPositions(dir, drive, "raw_run", "calib_cam_to_cam.txt");
  ExpectEvalWithKittiTruth(dir, "raw_run", "tracklet_labels.xml");
  ExpectRunWithPositions(dir, tracking, "tracking_run", "0000.txt");
  ExpectEvalWithKittiTruth(dir, "tracking_run", "label_02");

  // attend compare scores both against their labels too.
  r = Attend(dir, {"compare", "raw_run", "tracking_run", "--out", "cmp"});
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string comparison = ReadText(dir.File("cmp/summary.json"));
  EXPECT_TRUE(Contains(comparison, "tracklet_labels.xml")) << comparison.substr(0, 2000);
  EXPECT_TRUE(Contains(comparison, "label_02")) << comparison.substr(0, 2000);

  // A malformed calibration: exit 3, the file, line and key named.
  std::string calib = kLabRig.Tracking();
  calib.replace(calib.find("\nP3: "), 5, "\nP3: 1 ");
  std::ofstream(dir.File("training/calib/0000.txt")) << calib;
  r = Attend(dir, {"run", "--sequence", tracking, "--out", "bad_run", "--quiet"});
  EXPECT_EQ(r.status, 3) << r.err;
  EXPECT_TRUE(Contains(r.err, "calib/0000.txt line 4: P3 must hold 12 numbers, got 13")) << r.err;
  // A malformed tracklet file: attend eval exits 3 naming its line.
  std::string xml = ReadText(drive + "/tracklet_labels.xml");
  xml.replace(xml.find("</w>"), 4, "</l>");
  std::ofstream(drive + "/tracklet_labels.xml") << xml;
  r = Attend(dir, {"eval", "raw_run"});
  EXPECT_EQ(r.status, 3) << r.err;
  EXPECT_TRUE(Contains(r.err, "tracklet_labels.xml line 10: </l> closes <w>")) << r.err;
  // A missing date folder calibration names the file.
  fs::remove(dir.File("2011_09_26/calib_cam_to_cam.txt"));
  r = Attend(dir, {"run", "--sequence", drive, "--out", "bad_raw", "--quiet"});
  EXPECT_EQ(r.status, 3) << r.err;
  EXPECT_TRUE(Contains(r.err, "calib_cam_to_cam.txt: missing")) << r.err;
}

}  // namespace
}  // namespace attend
