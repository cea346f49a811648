// KITTI's layouts and files (io/kitti_*.h): finding a raw drive and a tracking sequence, their
// calibration in both spellings, the tracklets' XML, the tracking labels and the scans, and a
// raw drive opened as a frame source.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "io/calibration_text.h"
#include "io/kitti_calibration.h"
#include "io/kitti_labels.h"
#include "io/kitti_layout.h"
#include "io/kitti_tracklets.h"
#include "io/sequence.h"
#include "io/stereo_calibration.h"
#include "tests/support/error_message.h"
#include "tests/support/kitti_maker.h"
#include "tests/support/temp_dir.h"

namespace attend {
namespace {

namespace fs = std::filesystem;
using testing::InputErrorOf;

std::vector<cv::Mat> Frames(int count, cv::Size size) {
  std::vector<cv::Mat> frames;
  for (int i = 0; i < count; ++i) frames.emplace_back(size, CV_8UC3, cv::Scalar(10 * i, 80, 200));
  return frames;
}

TEST(CalibrationText, ReadsKeysWithAndWithoutColonAndNamesTheLineOfABadValue) {
  const testing::TempDir dir;
  const std::string path = dir.Write("c.txt",
                                     "calib_time: 09-Jan-2012 13:57:47\n# note\n"
                                     "P2: 1 2 3\nR_rect 4 5\nT: 1 x 3\n");
  const CalibrationText file(path);
  EXPECT_EQ(file.Numbers("P2", 3), (std::vector<double>{1, 2, 3}));
  EXPECT_EQ(file.Numbers("R_rect", 2), (std::vector<double>{4, 5}));
  EXPECT_EQ(file.FirstOf({"R0_rect", "R_rect"}), "R_rect");
  const std::string count = InputErrorOf([&] { file.Numbers("P2", 12); });
  EXPECT_NE(count.find(path + " line 3: P2 must hold 12 numbers, got 3"), std::string::npos)
      << count;
  const std::string word = InputErrorOf([&] { file.Numbers("T", 3); });
  EXPECT_NE(word.find("line 5: T has 'x'"), std::string::npos) << word;
  EXPECT_NE(InputErrorOf([&] { file.Numbers("P3", 12); }).find("P3 is missing"), std::string::npos);
}

TEST(KittiLayout, FindsARawDriveAndATrackingSequenceButNotAnAttendFolder) {
  const testing::TempDir dir;
  const testing::KittiTestRig rig;
  const std::string drive =
      testing::WriteKittiRawDrive(dir, rig, Frames(2, rig.size), Frames(2, rig.size));
  const std::string tracking =
      testing::WriteKittiTracking(dir, rig, Frames(2, rig.size), Frames(2, rig.size));
  EXPECT_TRUE(IsKittiRawDrive(drive));
  EXPECT_FALSE(IsKittiTracking(drive));
  EXPECT_TRUE(IsKittiTracking(tracking));
  EXPECT_TRUE(IsKittiTracking(tracking + "/"));
  EXPECT_FALSE(IsKittiRawDrive(tracking));
  const std::optional<KittiSequence> raw = FindKittiSequence(drive);
  ASSERT_TRUE(raw.has_value());
  EXPECT_EQ(raw->layout, KittiLayout::kRawDrive);
  EXPECT_EQ(raw->name, "2011_09_26_drive_0001_sync");
  EXPECT_EQ(fs::path(raw->calibration), dir.path() / "2011_09_26");
  EXPECT_EQ(fs::path(raw->labels).filename(), "tracklet_labels.xml");
  EXPECT_EQ(fs::path(raw->ScanPath("0000000001")),
            fs::path(drive) / "velodyne_points" / "data" / "0000000001.bin");
  const std::optional<KittiSequence> track = FindKittiSequence(tracking);
  ASSERT_TRUE(track.has_value());
  EXPECT_EQ(track->name, "0000");
  EXPECT_EQ(fs::path(track->calibration), dir.path() / "training" / "calib" / "0000.txt");
  EXPECT_EQ(fs::path(track->labels), dir.path() / "training" / "label_02" / "0000.txt");
  fs::create_directories(fs::path(drive) / "left");  // attend's own layout wins
  EXPECT_FALSE(FindKittiSequence(drive).has_value());
  EXPECT_FALSE(FindKittiSequence(dir.path().string()).has_value());
}

TEST(KittiCalibration, RawAndTrackingGiveTheSameRig) {
  const testing::TempDir dir;
  const testing::KittiTestRig rig;
  const std::string date = dir.Write("date/calib_cam_to_cam.txt", rig.CamToCam());
  dir.Write("date/calib_velo_to_cam.txt", rig.VeloToCam());
  const KittiRig raw = ReadKittiRawCalibration(dir.File("date"), cv::Size());
  const KittiRig tracking =
      ReadKittiFrameCalibration(dir.Write("0000.txt", rig.Tracking()), rig.size);
  for (const KittiRig* r : {&raw, &tracking}) {
    EXPECT_EQ(r->stereo.image_size, rig.size);
    EXPECT_DOUBLE_EQ(r->stereo.focal_px(), 100.0);
    EXPECT_NEAR(r->stereo.baseline_m(), 0.54, 1e-12);
    EXPECT_DOUBLE_EQ(r->stereo.cy(), 50.0);
    // Velodyne (10, 1, -1.73): 1 m left and 1.73 m down; the left camera sits 0.06 m left of
    // camera 0.
    const cv::Vec3d x = r->LeftCameraFromVelo({10, 1, -1.73});
    EXPECT_NEAR(x[0], -0.94, 1e-12);
    EXPECT_NEAR(x[1], 1.73, 1e-12);
    EXPECT_NEAR(x[2], 10.0, 1e-12);
    EXPECT_NEAR(r->Project(x).y, 50 + 17.3, 1e-9);
  }
  fs::remove(dir.File("date/calib_velo_to_cam.txt"));
  EXPECT_TRUE(ReadKittiRawCalibration(dir.File("date"), cv::Size()).velo_source.empty());
  fs::remove(date);
  EXPECT_NE(InputErrorOf([&] {
              ReadKittiRawCalibration(dir.File("date"), cv::Size());
            }).find("calib_cam_to_cam.txt: missing"),
            std::string::npos);
}

TEST(KittiTracklets, ReadsOneCarAndNamesTheLineOfBadXml) {
  const testing::TempDir dir;
  const std::vector<KittiTracklet> tracklets =
      ReadKittiTracklets(dir.Write("t.xml", testing::OneCarTracklet(3)));
  ASSERT_EQ(tracklets.size(), 1u);
  EXPECT_EQ(tracklets[0].type, "Car");
  EXPECT_DOUBLE_EQ(tracklets[0].l, 4.0);
  ASSERT_EQ(tracklets[0].poses.size(), 3u);
  EXPECT_DOUBLE_EQ(tracklets[0].poses[2].tz, -1.73);
  EXPECT_EQ(tracklets[0].poses[2].state, 2);

  const std::string xml = testing::OneCarTracklet(1);
  std::string bad = xml;
  bad.replace(bad.find("</ty>"), 5, "</tz>");  // line 18 of the file
  const std::string path = dir.Write("bad.xml", bad);
  const std::string message = InputErrorOf([&] { ReadKittiTracklets(path); });
  EXPECT_NE(message.find(path + " line 18: </tz> closes <ty> of line 18"), std::string::npos)
      << message;
  bad = xml;
  bad.replace(bad.find("<count>1</count>\n\t\t\t<item_version>"), 16, "<count>2</count>");
  EXPECT_NE(InputErrorOf([&] {
              ReadKittiTracklets(dir.Write("count.xml", bad));
            }).find("<poses> has count 2 but 1 items"),
            std::string::npos);
  bad = xml;
  bad.replace(bad.find("<h>1.5</h>"), 10, "<h>tall</h>");
  EXPECT_NE(InputErrorOf([&] {
              ReadKittiTracklets(dir.Write("h.xml", bad));
            }).find("line 9: <h> holds 'tall', not a number"),
            std::string::npos);
  EXPECT_NE(InputErrorOf([&] { ParseXmlSubset("<a>x &amp; y</a>", "s"); }).find("s line 1"),
            std::string::npos);
  EXPECT_NE(InputErrorOf([&] { ParseXmlSubset("<a><b>1</b>", "s"); }).find("<a> is not closed"),
            std::string::npos);
}

TEST(KittiLabels, ReadsTrackingLabelsAndScansAndNamesBadLines) {
  const testing::TempDir dir;
  const std::string path =
      dir.Write("0000.txt",
                "0 1 Car 0 1 -1.57 88.25 51.9 113.25 71.625 1.5 2 4 0 1.73 10 -1.57\n\n"
                "1 -1 DontCare -1 -1 -10 0 0 10 10 -1 -1 -1 -1000 -1000 -1000 -10 0.5\n");
  const std::vector<KittiLabel> labels = ReadKittiTrackingLabels(path);
  ASSERT_EQ(labels.size(), 2u);
  EXPECT_EQ(labels[0].type, "Car");
  EXPECT_EQ(labels[0].occluded, 1);
  EXPECT_DOUBLE_EQ(labels[0].box.width, 25.0);
  EXPECT_DOUBLE_EQ(labels[0].location[2], 10.0);
  EXPECT_EQ(labels[1].track_id, -1);
  EXPECT_DOUBLE_EQ(labels[1].score, 0.5);
  const std::string bad = dir.Write("bad.txt", "0 1 Car 0 0 0 1 2 3\n");
  EXPECT_NE(InputErrorOf([&] { ReadKittiTrackingLabels(bad); }).find(bad + " line 1: 9 values"),
            std::string::npos);
  const std::string word = dir.Write("word.txt", "\n0 1 Car 0 0 0 1 2 3 x 1 1 1 0 0 5 0\n");
  EXPECT_NE(InputErrorOf([&] { ReadKittiTrackingLabels(word); }).find("line 2: value 10 ('x')"),
            std::string::npos);

  testing::WriteScan(dir.File("scan.bin"), testing::FlatGroundScan());
  EXPECT_EQ(ReadVelodyneScan(dir.File("scan.bin")).size(), testing::FlatGroundScan().size());
  dir.Write("short.bin", "0123456789");
  EXPECT_NE(InputErrorOf([&] { ReadVelodyneScan(dir.File("short.bin")); }).find("10 bytes"),
            std::string::npos);
}

TEST(KittiSource, OpensARawDriveWithItsOwnCalibrationAtTenFramesASecond) {
  const testing::TempDir dir;
  const testing::KittiTestRig rig;
  const std::string drive =
      testing::WriteKittiRawDrive(dir, rig, Frames(3, rig.size), Frames(3, rig.size));
  SequenceOptions options;
  options.source.folder = drive;
  options.resize = "native";
  std::unique_ptr<FrameSource> source = OpenFrameSource(options);
  EXPECT_EQ(source->info().frame_count, 3);
  EXPECT_DOUBLE_EQ(source->info().fps, 10.0);
  EXPECT_EQ(source->info().name, "2011_09_26_drive_0001_sync");
  ASSERT_NE(source->info().calibration, nullptr);
  EXPECT_NEAR(source->info().calibration->baseline_m(), 0.54, 1e-12);
  StereoFrame frame;
  ASSERT_TRUE(source->Next(&frame));
  EXPECT_NE(frame.right_path.find("image_03"), std::string::npos);

  // A --calib file wins over KITTI's own.
  options.source.calib = dir.File("calib.yaml");
  WriteStereoCalibration(NominalCalibration(80.0, 0.3, rig.size, "test"), options.source.calib);
  EXPECT_NEAR(OpenFrameSource(options)->info().calibration->baseline_m(), 0.3, 1e-12);
  options.source.calib.clear();

  // A size that is not the frames' (S_rect_02 says 200x100): named with both sizes.
  std::ofstream(dir.File("2011_09_26/calib_cam_to_cam.txt"))
      << testing::KittiTestRig{100, 100, 50, 0.54, {300, 100}}.CamToCam();
  EXPECT_NE(InputErrorOf([&] { OpenFrameSource(options); }).find("300x100"), std::string::npos);
  fs::remove(dir.File("2011_09_26/calib_cam_to_cam.txt"));
  EXPECT_NE(InputErrorOf([&] { OpenFrameSource(options); }).find("calib_cam_to_cam.txt"),
            std::string::npos);
  fs::remove(fs::path(drive) / "image_03" / "data" / "0000000002.png");
  EXPECT_NE(InputErrorOf([&] { OpenFrameSource(options); }).find("has 3 frames but"),
            std::string::npos);
}

}  // namespace
}  // namespace attend
