// Where attention lands (eval/landing.h) on hand-built truth whose answers are known: a 100 x
// 100 frame with the horizon at row 50, ground points below it, an object standing on the
// ground and a wall of points far away above the horizon on the right.
#include "eval/landing.h"

#include <gtest/gtest.h>

#include <cmath>
#include <tuple>
#include <vector>

namespace attend {
namespace {

const cv::Rect2d kObjectBox(10, 60, 20, 20);
const cv::Rect2d kWallBox(70, 30, 30, 20);

FrameTruth StreetFrame(int frame, bool with_object = true) {
  FrameTruth truth;
  truth.frame = frame;
  truth.image_size = {100, 100};
  truth.horizon = {0.0, 1.0, -50.0};
  for (int v = 0; v < 100; v += 2) {
    for (int u = 0; u < 100; u += 2) {
      TruthPoint p;
      p.u = u, p.v = v;
      if (with_object && kObjectBox.contains(cv::Point2d(u, v))) {
        p.depth_m = 8.f;
      } else if (kWallBox.contains(cv::Point2d(u, v))) {
        p.depth_m = 50.f;
      } else if (v > 50) {
        p.depth_m = 10.f;
        p.ground = true;
      } else {
        continue;  // the sky: no point
      }
      truth.points.push_back(p);
    }
  }
  if (with_object) truth.objects.push_back({7, kObjectBox, "car", 8.0});
  return truth;
}

TargetRecord Target(int id, const cv::Rect& box, TargetState state = TargetState::kTracked) {
  TargetRecord t;
  t.id = id;
  t.bbox = box;
  t.area = box.area();
  t.state = state;
  return t;
}

TEST(Landing, SkyGroundObjectAndElsewhere) {
  SceneTruth truth = {{0, StreetFrame(0)}};
  FrameRecord record;
  record.frame = 0;
  record.targets = {Target(1, {40, 10, 20, 20}),   // sky: no points, centre above row 50
                    Target(2, {40, 70, 20, 20}),   // ground
                    Target(3, {12, 62, 16, 16}),   // inside the object
                    Target(4, {72, 34, 20, 12}),   // the wall: points, not ground
                    Target(5, {0, 0, 8, 8}, TargetState::kOccluded)};  // not seen: not counted
  const LandingScores s = EvaluateLanding({record}, truth);
  EXPECT_EQ(s.frames, 1);
  EXPECT_EQ(s.target_frames, 4);
  EXPECT_EQ(s.on_sky, 1);
  EXPECT_EQ(s.on_ground, 1);
  EXPECT_EQ(s.on_object, 1);
  EXPECT_EQ(s.without_depth, 1);
  EXPECT_EQ(s.elsewhere, 1);
  EXPECT_DOUBLE_EQ(s.Share(s.on_sky), 0.25);
  ASSERT_EQ(s.objects.size(), 1u);
  EXPECT_EQ(s.objects[0].first_attended, 0);
}

TEST(Landing, ABoxWhoseInnerHalfIsMostlyGroundIsOnTheGround) {
  SceneTruth truth = {{0, StreetFrame(0)}};
  FrameRecord record;
  record.frame = 0;
  // Inner half (25, 65, 20, 20): 10 x 10 points, of which columns 26 and 28 at rows 66..78
  // (14) are on the object: 86 % ground, >= 0.7.
  record.targets = {Target(1, {15, 55, 40, 40})};
  EXPECT_EQ(EvaluateLanding({record}, truth).on_ground, 1);
  // Inner half (15, 65, 20, 20): columns 16..28 at rows 66..78 (49) on the object: 51 %.
  record.targets = {Target(1, {5, 55, 40, 40})};
  EXPECT_EQ(EvaluateLanding({record}, truth).on_ground, 0);
}

TEST(Landing, NoDepthBelowTheHorizonIsNotSky) {
  FrameTruth frame = StreetFrame(0);
  frame.points.clear();
  SceneTruth truth = {{0, frame}};
  FrameRecord record;
  record.frame = 0;
  record.targets = {Target(1, {40, 70, 20, 20}), Target(2, {40, 10, 20, 20})};
  LandingScores s = EvaluateLanding({record}, truth);
  EXPECT_EQ(s.without_depth, 2);
  EXPECT_EQ(s.on_sky, 1);
  EXPECT_EQ(s.elsewhere, 1);
  // Without a horizon, no point is enough.
  truth[0].horizon = {};
  s = EvaluateLanding({record}, truth);
  EXPECT_EQ(s.on_sky, 2);
}

TEST(Landing, OnObjectByCoverOrByIou) {
  SceneTruth truth = {{0, StreetFrame(0)}};
  FrameRecord record;
  record.frame = 0;
  // Half its area on the object (cover 0.5, IoU 200 / 600 = 0.33): on it.
  // A box four times the object's area around it: cover 0.25, IoU 0.25: not on it.
  // A box 20 x 10 over its top half: cover 1.
  record.targets = {Target(1, {20, 60, 20, 20}), Target(2, {0, 50, 40, 40}),
                    Target(3, {10, 60, 20, 10})};
  const LandingScores s = EvaluateLanding({record}, truth);
  EXPECT_EQ(s.on_object, 2);
}

TEST(Landing, ObjectShareInViewCountsOnlyFramesWithObjects) {
  SceneTruth truth = {{0, StreetFrame(0)}, {1, StreetFrame(1, false)}};
  FrameRecord a, b, c;
  a.frame = 0;
  a.targets = {Target(1, {12, 62, 16, 16}), Target(2, {40, 70, 20, 20})};
  b.frame = 1;
  b.targets = {Target(1, {12, 62, 16, 16}), Target(2, {40, 70, 20, 20}),
               Target(3, {40, 10, 20, 20})};
  c.frame = 5;  // no truth: skipped
  c.targets = {Target(1, {12, 62, 16, 16})};
  const LandingScores s = EvaluateLanding({a, b, c}, truth);
  EXPECT_EQ(s.frames, 2);
  EXPECT_EQ(s.frames_without_truth, 1);
  EXPECT_EQ(s.target_frames, 5);
  EXPECT_EQ(s.frames_with_objects, 1);
  EXPECT_DOUBLE_EQ(s.ObjectShareInView(), 0.5);
  EXPECT_DOUBLE_EQ(s.Share(s.on_object), 0.2);
}

TEST(Landing, FirstAttendedFramesAndTheWindow) {
  // Object 7 from frame 0, attended first at frame 12; object 8 from frame 3, attended at 5;
  // object 9 from frame 0, never attended.
  SceneTruth truth;
  std::vector<FrameRecord> records;
  const cv::Rect2d box8(60, 60, 20, 20), box9(40, 80, 10, 10);
  for (int f = 0; f < 20; ++f) {
    FrameTruth frame = StreetFrame(f);
    if (f >= 3) frame.objects.push_back({8, box8, "person", 10.0});
    frame.objects.push_back({9, box9, "cyclist", 10.0});
    truth[f] = frame;
    FrameRecord record;
    record.frame = f;
    if (f >= 12) record.targets.push_back(Target(1, {10, 60, 20, 20}));
    if (f >= 5) record.targets.push_back(Target(2, {60, 60, 20, 20}));
    records.push_back(record);
  }
  const LandingScores s = EvaluateLanding(records, truth);
  ASSERT_EQ(s.objects.size(), 3u);
  EXPECT_EQ(s.objects[0].id, 7);
  EXPECT_EQ(s.objects[0].first_visible, 0);
  EXPECT_EQ(s.objects[0].first_attended, 12);
  EXPECT_EQ(s.objects[0].frames_to_attend, 12);
  EXPECT_EQ(s.objects[1].first_visible, 3);
  EXPECT_EQ(s.objects[1].frames_to_attend, 2);
  EXPECT_FALSE(s.objects[2].first_attended.has_value());
  EXPECT_EQ(s.attended_within, 1);
  const nlohmann::ordered_json json = LandingToJson(s);
  EXPECT_TRUE(json["per_object"][2]["first_attended"].is_null());
  EXPECT_EQ(json["attended_within"], 1);
}

TEST(Landing, DepthAgainstTheMedianOfTheInnerHalf) {
  FrameTruth frame = StreetFrame(0);
  frame.points.clear();
  // Inner half of box (0, 0, 40, 40) is (10, 10, 20, 20): points 8, 10, 12, 100 there (median
  // 11); one point at 50 outside it. Box (60, 60, 8, 8): inner (62, 62, 4, 4), three points at 10.
  for (const auto& [u, v, z] : std::vector<std::tuple<float, float, float>>{
           {12, 12, 8}, {14, 12, 10}, {16, 12, 12}, {18, 12, 100}, {2, 2, 50},
           {62, 62, 10}, {63, 63, 10}, {64, 64, 10}, {90, 90, 10}, {91, 91, 10}}) {
    TruthPoint p;
    p.u = u, p.v = v, p.depth_m = z;
    frame.points.push_back(p);
  }
  SceneTruth truth = {{0, frame}};
  FrameRecord record;
  record.frame = 0;
  TargetRecord a = Target(1, {0, 0, 40, 40}), b = Target(2, {60, 60, 8, 8}),
               c = Target(3, {85, 85, 12, 12}), d = Target(4, {0, 0, 40, 40});
  a.has_position = b.has_position = c.has_position = true;
  a.position_m = {0, 0, 11};
  b.position_m = {0, 0, 9.5};
  c.position_m = {0, 0, 3};  // two points only: no depth
  record.targets = {a, b, c, d};  // d has no position
  const LandingScores s = EvaluateLanding({record}, truth);
  EXPECT_EQ(s.depth_target_frames, 2);
  EXPECT_DOUBLE_EQ(s.depth_share_within, 1.0);
  EXPECT_NEAR(s.median_relative_depth_error, 0.025, 1e-12);
  EXPECT_NEAR(s.median_abs_depth_error_m, 0.25, 1e-12);
}

TEST(Landing, JsonHoldsEveryKey) {
  const nlohmann::ordered_json json = LandingToJson(EvaluateLanding({}, {}));
  for (const char* key :
       {"frames", "frames_without_truth", "target_frames", "on_object", "on_sky", "on_ground",
        "without_depth", "elsewhere", "on_object_share", "on_sky_share", "on_ground_share",
        "without_depth_share", "elsewhere_share", "frames_with_objects",
        "target_frames_with_objects", "object_share_in_view", "objects", "attended_window",
        "attended_within", "per_object", "depth"}) {
    EXPECT_TRUE(json.contains(key)) << key;
  }
  EXPECT_TRUE(json["on_sky_share"].is_null());
  EXPECT_TRUE(json["depth"]["median_relative_error"].is_null());
}

}  // namespace
}  // namespace attend
