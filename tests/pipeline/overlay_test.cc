// The overlay (pipeline/overlay.h): each target's depth beside its id, as a position's Z in
// metres or else as the record's disparity in pixels.
#include "pipeline/overlay.h"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

namespace attend {
namespace {

TargetRecord Target(int id, cv::Rect box) {
  TargetRecord target;
  target.id = id;
  target.bbox = box;
  target.state = TargetState::kTracked;
  return target;
}

TEST(Overlay, DepthLabelIsZInMetresOrElseTheDisparity) {
  TargetRecord target = Target(3, {40, 40, 30, 30});
  EXPECT_EQ(TargetDepthLabel(target), "");
  target.disparity_px = 12.345;
  target.disparity_sd_px = 0.4;
  EXPECT_EQ(TargetDepthLabel(target), " d 12.3 px");
  target.has_position = true;
  target.position_m = cv::Vec3d(-0.3, 0.1, 2.4149);
  target.position_sd_m = cv::Vec3d(0.01, 0.01, 0.08);
  EXPECT_EQ(TargetDepthLabel(target), " Z 2.41 m");
  // One decimal of a disparity, rounded.
  TargetRecord far = Target(4, {0, 0, 4, 4});
  far.disparity_px = 0.96;
  EXPECT_EQ(TargetDepthLabel(far), " d 1.0 px");
}

// The label is drawn: the pixels in the label's row beside the id differ with and without it.
TEST(Overlay, DrawsTheDepthBesideTheId) {
  const cv::Mat left(120, 240, CV_8UC3, cv::Scalar(90, 90, 90));
  FrameRecord record;
  record.frame = 7;
  record.targets.push_back(Target(1, {20, 50, 40, 40}));
  const cv::Mat plain = DrawOverlay(left, record);
  record.targets[0].has_position = true;
  record.targets[0].position_m = cv::Vec3d(0.0, 0.0, 2.41);
  const cv::Mat with_depth = DrawOverlay(left, record);
  // The label's baseline is 3 px above the box; "#1" alone ends well before x = 60.
  const cv::Rect beyond_id(50, 30, 140, 20);
  cv::Mat difference;
  cv::absdiff(plain(beyond_id), with_depth(beyond_id), difference);
  cv::cvtColor(difference, difference, cv::COLOR_BGR2GRAY);
  EXPECT_GT(cv::countNonZero(difference), 30);
  // Outside the label's row nothing changes.
  cv::absdiff(plain(cv::Rect(0, 52, 240, 68)), with_depth(cv::Rect(0, 52, 240, 68)), difference);
  cv::cvtColor(difference, difference, cv::COLOR_BGR2GRAY);
  EXPECT_EQ(cv::countNonZero(difference), 0);
}

// A box at the right edge: its label, longer with the depth, moves left to stay whole.
TEST(Overlay, ALabelAtTheRightEdgeMovesLeftToStayInTheImage) {
  const cv::Mat left(120, 240, CV_8UC3, cv::Scalar(90, 90, 90));
  FrameRecord record;
  record.targets.push_back(Target(1, {220, 50, 20, 40}));
  record.targets[0].has_position = true;
  record.targets[0].position_m = cv::Vec3d(0.0, 0.0, 12.5);
  const cv::Mat overlay = DrawOverlay(left, record);
  cv::Mat difference;
  cv::absdiff(overlay(cv::Rect(0, 30, 240, 20)), left(cv::Rect(0, 30, 240, 20)), difference);
  cv::cvtColor(difference, difference, cv::COLOR_BGR2GRAY);
  // Drawn left of the box, and not cut at the right edge: its last column is background.
  EXPECT_GT(cv::countNonZero(difference(cv::Rect(150, 0, 70, 20))), 30);
  EXPECT_LT(cv::countNonZero(difference(cv::Rect(239, 0, 1, 20))), 3);
}

// A target released and resumed under its id in one frame (configs/people.yaml): both boxes
// are drawn, and only the resumed one is labelled.
TEST(Overlay, AReleasedTargetResumedInItsFrameIsLabelledOnce) {
  const cv::Mat left(120, 240, CV_8UC3, cv::Scalar(90, 90, 90));
  FrameRecord resumed_only;
  resumed_only.targets.push_back(Target(7, {150, 60, 40, 40}));
  resumed_only.targets[0].state = TargetState::kResumed;
  FrameRecord both = resumed_only;
  both.targets.insert(both.targets.begin(), Target(7, {20, 60, 40, 40}));
  both.targets[0].state = TargetState::kReleased;
  cv::Mat difference;
  cv::absdiff(DrawOverlay(left, both), DrawOverlay(left, resumed_only), difference);
  cv::cvtColor(difference, difference, cv::COLOR_BGR2GRAY);
  // No label above the released box: its row (the box's top edge is at y = 60) is unchanged.
  EXPECT_EQ(cv::countNonZero(difference(cv::Rect(0, 40, 140, 19))), 0);
  // Its box is drawn.
  EXPECT_GT(cv::countNonZero(difference(cv::Rect(19, 59, 43, 43))), 100);
  // A released target that nobody resumed keeps its label.
  FrameRecord released_only;
  released_only.targets.push_back(both.targets[0]);
  cv::absdiff(DrawOverlay(left, released_only), left, difference);
  cv::cvtColor(difference, difference, cv::COLOR_BGR2GRAY);
  EXPECT_GT(cv::countNonZero(difference(cv::Rect(0, 40, 140, 19))), 30);
}

}  // namespace
}  // namespace attend
