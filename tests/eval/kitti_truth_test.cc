// The ground truth of KITTI sequences (eval/kitti_truth.h, eval/lidar_ground.h,
// eval/lidar_depth.h) on a rig whose answers are worked out by hand (tests/support/kitti_maker.h),
// and on the real frame of the shared data when it is there.
#include "eval/kitti_truth.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <iostream>
#include <opencv2/imgcodecs.hpp>

#include "eval/lidar_depth.h"
#include "eval/lidar_ground.h"
#include "tests/support/kitti_maker.h"
#include "tests/support/temp_dir.h"
#include "util/error.h"

namespace attend {
namespace {

namespace fs = std::filesystem;

std::vector<cv::Mat> Frames(int count, cv::Size size) {
  return std::vector<cv::Mat>(static_cast<size_t>(count), cv::Mat(size, CV_8UC3, cv::Scalar(90)));
}

KittiRig TestRig(const testing::TempDir& dir) {
  const testing::KittiTestRig rig;
  dir.Write("date/calib_cam_to_cam.txt", rig.CamToCam());
  dir.Write("date/calib_velo_to_cam.txt", rig.VeloToCam());
  return ReadKittiRawCalibration(dir.File("date"), cv::Size());
}

void ExpectBox(const cv::Rect2d& box, const cv::Rect2d& expected) {
  EXPECT_NEAR(box.x, expected.x, 1e-9);
  EXPECT_NEAR(box.y, expected.y, 1e-9);
  EXPECT_NEAR(box.width, expected.width, 1e-9);
  EXPECT_NEAR(box.height, expected.height, 1e-9);
}

TEST(LidarGroundOptions, DefaultsAreValidAndACheckNamesTheField) {
  EXPECT_EQ(LidarGroundOptions{}.Check(), "");
  LidarGroundOptions options;
  options.max_tilt_deg = 90;
  EXPECT_NE(options.Check().find("max_tilt_deg"), std::string::npos);
  options = LidarGroundOptions{};
  options.min_points = 2;
  EXPECT_NE(options.Check().find("min_points"), std::string::npos);
}

TEST(KittiTruth, TooFewPointsBelowTheCameraGiveNoPlane) {
  std::vector<cv::Vec3d> points = {{0, 1.7, 5}, {1, 1.7, 6}, {-1, 1.7, 7}, {0, -1, 8}};
  EXPECT_FALSE(FitLidarGroundPlane(points).found);
  // A wall (normal along X) is not the ground, however many points it has.
  points.clear();
  for (int y = 1; y < 10; ++y) {
    for (int z = 2; z < 12; ++z) points.emplace_back(2.0, 0.2 * y, z);
  }
  EXPECT_FALSE(FitLidarGroundPlane(points).found);
}

TEST(KittiTruth, ATrackletProjectsToTheBoxWorkedOutByHand) {
  const testing::TempDir dir;
  const KittiRig rig = TestRig(dir);
  std::vector<KittiTracklet> tracklets =
      ReadKittiTracklets(dir.Write("t.xml", testing::OneCarTracklet(2)));
  std::vector<TruthObject> objects = TrackletObjects(tracklets, rig, {200, 100}, 1);
  ASSERT_EQ(objects.size(), 1u);
  ExpectBox(objects[0].box, testing::CarBox());
  EXPECT_NEAR(objects[0].depth_m, 10.0, 1e-12);
  EXPECT_EQ(objects[0].kind, "Car");
  EXPECT_TRUE(TrackletObjects(tracklets, rig, {200, 100}, 2).empty());  // no pose there
  // Clipped to a narrower image: the box ends at its right edge.
  objects = TrackletObjects(tracklets, rig, {100, 100}, 0);
  ASSERT_EQ(objects.size(), 1u);
  EXPECT_NEAR(objects[0].box.width, 100 - 88.25, 1e-9);
  // Beside the camera (corners behind it) or out of view: dropped.
  tracklets[0].poses[0].tx = 1.0;
  EXPECT_TRUE(TrackletObjects(tracklets, rig, {200, 100}, 0).empty());
  tracklets[0].poses[0].tx = 10.0;
  tracklets[0].poses[0].ty = 30.0;
  EXPECT_TRUE(TrackletObjects(tracklets, rig, {200, 100}, 0).empty());
}

TEST(KittiTruth, TheGroundIsFoundFlaggedAndGivesTheHorizonAtTheLevelCamerasPrincipalRow) {
  const testing::TempDir dir;
  const KittiRig rig = TestRig(dir);
  const LidarTruth truth = ProjectScan(testing::FlatGroundScan(), rig, {200, 100});
  ASSERT_TRUE(truth.plane.found);
  EXPECT_NEAR(truth.plane.camera_height_m(), 1.73, 1e-6);
  EXPECT_NEAR(truth.plane.normal[1], -1.0, 1e-9);
  int ground = 0, car = 0;
  for (const TruthPoint& p : truth.points) {
    EXPECT_GT(p.depth_m, kMinPointDepthM);
    EXPECT_TRUE(p.u >= 0 && p.u < 200 && p.v >= 0 && p.v < 100);
    // The ground points image below the horizon, v = 50 + 173 / depth; the car's rear at 8 m.
    if (p.ground) {
      ++ground;
      EXPECT_NEAR(p.v, 50 + 173 / p.depth_m, 1e-3);
    } else {
      ++car;
      EXPECT_NEAR(p.depth_m, 8.0, 1e-5);
    }
  }
  EXPECT_EQ(car, 9);
  EXPECT_EQ(ground, truth.plane.inliers);
  EXPECT_GT(ground, 100);
  ASSERT_TRUE(truth.horizon.valid());
  EXPECT_NEAR(truth.horizon.HorizonV(0), 50.0, 1e-9);
  EXPECT_NEAR(truth.horizon.HorizonV(199), 50.0, 1e-9);
}

TEST(KittiTruth, TheHorizonHoldsTheVanishingPointsOfATiltedPlane) {
  const cv::Matx33d K(700, 0, 600, 0, 700, 180, 0, 0, 1);
  cv::Vec3d normal(0.05, -0.99, 0.1);
  normal /= cv::norm(normal);
  const HorizonLine horizon = HorizonOfPlane(normal, K);
  // Two directions in the plane, ahead of the camera: their images are on the horizon.
  const cv::Vec3d ahead = normal.cross(cv::Vec3d(1, 0, 0));
  for (const cv::Vec3d& direction : {ahead, ahead + 0.3 * normal.cross(ahead)}) {
    ASSERT_NEAR(direction.dot(normal), 0.0, 1e-12);
    const cv::Vec3d x = K * direction;
    EXPECT_NEAR(horizon.HorizonV(x[0] / x[2]), x[1] / x[2], 1e-6);
  }
  // Pitched down (the normal leans towards the camera's -Z): the horizon rises above cy.
  EXPECT_LT(HorizonOfPlane(cv::Vec3d(0, -0.99, -0.14), K).HorizonV(600), 180.0);
}

TEST(KittiTruth, ReadsBothLayoutsIntoSceneTruthAndObjects) {
  const testing::TempDir dir;
  const testing::KittiTestRig rig;
  const std::string drive =
      testing::WriteKittiRawDrive(dir, rig, Frames(3, rig.size), Frames(3, rig.size));
  const std::string tracking =
      testing::WriteKittiTracking(dir, rig, Frames(3, rig.size), Frames(3, rig.size));
  for (const std::string& folder : {drive, tracking}) {
    SCOPED_TRACE(folder);
    const KittiSequence sequence = *FindKittiSequence(folder);
    const SceneTruth truth = ReadKittiTruth(sequence);
    ASSERT_EQ(truth.size(), 3u);
    const FrameTruth& frame = truth.at(2);
    EXPECT_EQ(frame.image_size, rig.size);
    ASSERT_EQ(frame.objects.size(), 1u);  // DontCare left out
    ExpectBox(frame.objects[0].box, sequence.layout == KittiLayout::kRawDrive
                                        ? testing::CarBox()
                                        : cv::Rect2d(88.25, 51.9166, 25, 71.625 - 51.9166));
    EXPECT_NEAR(frame.objects[0].depth_m, 10.0, 1e-9);
    EXPECT_EQ(frame.points.size(),
              ProjectScan(testing::FlatGroundScan(), TestRig(dir), rig.size).points.size());
    EXPECT_NEAR(frame.horizon.HorizonV(100), 50.0, 1e-9);
    const std::vector<GtObject> objects = ReadKittiObjects(sequence);
    ASSERT_EQ(objects.size(), 3u);
    EXPECT_EQ(objects[1].frame, 1);
    EXPECT_EQ(objects[1].kind, "Car");
    EXPECT_DOUBLE_EQ(objects[1].visible_fraction, 1.0);
    ASSERT_TRUE(objects[1].disparity.has_value());
    EXPECT_NEAR(*objects[1].disparity, 100 * 0.54 / 10, 1e-9);
  }
  fs::remove(fs::path(drive) / "tracklet_labels.xml");
  EXPECT_THROW(ReadKittiObjects(*FindKittiSequence(drive)), InputError);
  EXPECT_DOUBLE_EQ(KittiVisibleFraction(2), 0.2);
}

TEST(LidarDepth, ScoresTargetsAgainstTheMedianOfThePointsInTheirBoxesInnerHalf) {
  FrameTruth frame;
  // Points at 10 m inside the inner half of (40, 40, 40, 40) (50..70), one at 30 m outside it.
  for (float u : {52.f, 60.f, 68.f}) frame.points.push_back({u, 60.f, 10.f, false});
  frame.points.push_back({42.f, 42.f, 30.f, false});
  const SceneTruth truth = {{0, frame}, {1, frame}};
  FrameRecord record;
  TargetRecord target;
  target.bbox = cv::Rect(40, 40, 40, 40);
  target.has_position = true;
  target.position_m = cv::Vec3d(0, 0, 10.5);
  record.targets = {target};
  target.state = TargetState::kOccluded;  // not seen: not scored
  record.targets.push_back(target);
  FrameRecord second = record;
  second.frame = 1;
  second.targets[0].position_m[2] = 12.0;
  const LidarDepthScores scores = EvaluateLidarDepth({record, second}, truth);
  EXPECT_EQ(scores.count, 2);
  EXPECT_DOUBLE_EQ(scores.share_within_10_percent, 0.5);
  EXPECT_NEAR(scores.median_relative_error, 0.125, 1e-12);
  EXPECT_NEAR(scores.median_abs_error_m, 1.25, 1e-12);
  // Fewer than 3 points: not scored.
  frame.points.resize(2);
  EXPECT_EQ(EvaluateLidarDepth({record}, {{0, frame}}).count, 0);
}

// The real KITTI frame of the shared data (object layout): the ground under a camera 1.65 m
// up, and a horizon near the middle of KITTI's 375 rows.
TEST(KittiTruth, TheSharedKittiPairHasItsGroundAndHorizonWhereKittisRigPutsThem) {
  const fs::path pair = fs::path(testing::SharedData()) / "kitti_pair";
  if (!fs::exists(pair / "velodyne" / "000000.bin")) GTEST_SKIP() << pair << " is absent";
  const cv::Mat image = cv::imread((pair / "image_2" / "000000.png").string());
  ASSERT_FALSE(image.empty());
  const LidarTruth truth =
      ReadKittiObjectFrame((pair / "calib" / "000000.txt").string(),
                           (pair / "velodyne" / "000000.bin").string(), image.size());
  ASSERT_TRUE(truth.plane.found);
  const int ground = truth.plane.inliers;
  std::cout << "kitti_pair: " << image.cols << "x" << image.rows << ", " << truth.points.size()
            << " points in the image, " << ground << " on the ground ("
            << 100.0 * ground / truth.points.size() << " %), camera height "
            << truth.plane.camera_height_m() << " m, normal " << truth.plane.normal
            << ", horizon row " << truth.horizon.HorizonV(0) << " (u 0) "
            << truth.horizon.HorizonV(image.cols / 2.0) << " (centre) "
            << truth.horizon.HorizonV(image.cols - 1) << " (u " << image.cols - 1 << ")\n";
  EXPECT_GT(truth.points.size(), 10000u);
  EXPECT_GT(truth.plane.camera_height_m(), 1.6);
  EXPECT_LT(truth.plane.camera_height_m(), 1.8);
  EXPECT_GT(truth.horizon.HorizonV(image.cols / 2.0), 160.0);
  EXPECT_LT(truth.horizon.HorizonV(image.cols / 2.0), 200.0);
}

}  // namespace
}  // namespace attend
