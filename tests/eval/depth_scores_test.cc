// The targets' disparity and depth errors (eval/depth_scores.h) on records and objects whose
// errors are known by construction.
#include "eval/depth_scores.h"

#include <gtest/gtest.h>

namespace attend {
namespace {

GtObject KnownObject(int frame, int id, cv::Rect2d box, double disparity) {
  GtObject object;
  object.frame = frame;
  object.id = id;
  object.box = box;
  object.visible_fraction = 1.0;
  object.disparity = disparity;
  return object;
}

TargetRecord DepthTarget(int id, cv::Rect box, double disparity, double sd) {
  TargetRecord target;
  target.id = id;
  target.bbox = box;
  target.state = TargetState::kTracked;
  target.disparity_px = disparity;
  target.disparity_sd_px = sd;
  return target;
}

TEST(TargetDepthScores, ErrorsOfTheMatchedTargetsOnly) {
  // Object 1 at 10 px, object 2 at 4 px (farther than near_disparity 8).
  const std::vector<GtObject> truth = {KnownObject(0, 1, {0, 0, 20, 20}, 10.0),
                                       KnownObject(0, 2, {50, 50, 20, 20}, 4.0),
                                       KnownObject(1, 1, {0, 0, 20, 20}, 10.0)};
  FrameRecord f0, f1;
  f0.frame = 0;
  f1.frame = 1;
  f0.targets = {DepthTarget(1, {0, 0, 20, 20}, 10.1, 0.2),     // error 0.1, within 1 sd
                DepthTarget(2, {50, 50, 20, 20}, 4.5, 0.2),    // error 0.5, beyond 2 sd
                DepthTarget(3, {100, 100, 9, 9}, 7.0, 0.2)};   // on no object
  f1.targets = {DepthTarget(1, {1, 1, 20, 20}, 9.5, 0.3)};     // error 0.5, within 2 sd
  TargetRecord released = DepthTarget(1, {0, 0, 20, 20}, 3.0, 0.1);
  released.state = TargetState::kReleased;                // not seen: not scored
  f1.targets.push_back(released);
  const DepthScores s = EvaluateTargetDepth({f0, f1}, truth);
  EXPECT_EQ(s.matches, 3);
  EXPECT_NEAR(s.median_abs_error_px, 0.5, 1e-9);
  EXPECT_NEAR(s.mean_abs_error_px, (0.1 + 0.5 + 0.5) / 3, 1e-9);
  EXPECT_NEAR(s.share_within_quarter_px, 1.0 / 3, 1e-9);
  EXPECT_NEAR(s.share_within_1_sd, 1.0 / 3, 1e-9);
  EXPECT_NEAR(s.share_within_2_sd, 2.0 / 3, 1e-9);
  // Near objects only (object 1): |10 / 10.1 - 1| and |10 / 9.5 - 1|.
  EXPECT_EQ(s.near_matches, 2);
  EXPECT_NEAR(s.median_depth_error, (std::abs(10 / 10.1 - 1) + std::abs(10 / 9.5 - 1)) / 2, 1e-9);
  EXPECT_NEAR(s.share_depth_within_2_percent, 0.5, 1e-9);
}

TEST(TargetDepthScores, NothingToScoreWithoutDisparities) {
  const std::vector<GtObject> truth = {KnownObject(0, 1, {0, 0, 20, 20}, 10.0)};
  FrameRecord f0;
  TargetRecord mono = DepthTarget(1, {0, 0, 20, 20}, 0.0, 0.0);
  mono.disparity_px = std::numeric_limits<double>::quiet_NaN();
  f0.targets = {mono};
  EXPECT_EQ(EvaluateTargetDepth({f0}, truth).matches, 0);
  EXPECT_LT(EvaluateTargetDepth({f0}, truth).median_abs_error_px, 0.0);
}

}  // namespace
}  // namespace attend
