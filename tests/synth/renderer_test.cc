#include "synth/renderer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgproc.hpp>

#include "util/error.h"

namespace attend {
namespace {

// focal_px * baseline_m = 10 exactly, so depths 1, 2, 5 give disparities 10, 5, 2.
constexpr double kFocal = 80.0;
constexpr double kBaseline = 0.125;

Scene BaseScene() {
  Scene scene;
  scene.name = "test";
  scene.width = 64;
  scene.height = 48;
  scene.frames = 10;
  scene.seed = 3;
  scene.focal_px = kFocal;
  scene.baseline_m = kBaseline;
  scene.noise_left = 0.0;
  scene.noise_right = 0.0;
  scene.background.depth_m = 5.0;
  scene.background.colour = {120, 120, 120};
  scene.background.texture = 0.0;
  return scene;
}

// An object whose projected size is width_px x height_px at `depth`.
SceneObject Box(int id, double x, double y, double depth, double width_px, double height_px,
                Rgb colour = {200, 40, 40}) {
  SceneObject o;
  o.id = id;
  o.name = "box" + std::to_string(id);
  o.width_m = width_px * depth / kFocal;
  o.height_m = height_px * depth / kFocal;
  o.colour = colour;
  o.path = {{0, x, y, depth}};
  return o;
}

const GtObject* FindGt(const RenderedFrame& frame, int id) {
  for (const GtObject& gt : frame.objects) {
    if (gt.id == id) return &gt;
  }
  return nullptr;
}

cv::Rect BoxOfId(const cv::Mat& ids, int id) {
  const cv::Mat mask = ids == id;
  return cv::boundingRect(mask);
}

TEST(SceneRenderer, RejectsAnInvalidScene) {
  Scene scene = BaseScene();
  scene.background.depth_m = -1;
  EXPECT_THROW(SceneRenderer{scene}, ConfigError);
}

TEST(SceneRenderer, DisparityIsFocalTimesBaselineOverDepthOfTheNearestSurface) {
  Scene scene = BaseScene();
  scene.objects = {Box(1, 20, 20, 2.0, 20, 16), Box(2, 28, 24, 1.0, 14, 14),
                   Box(3, 50, 30, 4.0, 10, 10)};
  scene.objects[2].shape = SynthShape::kEllipse;
  const RenderedFrame frame = SceneRenderer(scene).Render(0);
  ASSERT_EQ(frame.disparity.type(), CV_32FC1);
  const std::map<int, double> depth_of = {{0, 5.0}, {1, 2.0}, {2, 1.0}, {3, 4.0}};
  std::map<int, int> count;
  for (int y = 0; y < scene.height; ++y) {
    for (int x = 0; x < scene.width; ++x) {
      const int id = frame.left_ids.at<int>(y, x);
      ++count[id];
      EXPECT_FLOAT_EQ(frame.disparity.at<float>(y, x),
                      static_cast<float>(kFocal * kBaseline / depth_of.at(id)))
          << x << "," << y;
    }
  }
  for (int id = 0; id <= 3; ++id) EXPECT_GT(count[id], 20) << id;
  // Object 2 (depth 1) lies in front of object 1 (depth 2) where they overlap, although it is
  // listed after it.
  EXPECT_EQ(frame.left_ids.at<int>(24, 28), 2);
  EXPECT_EQ(frame.left_ids.at<int>(14, 12), 1);
  EXPECT_DOUBLE_EQ(FindGt(frame, 2)->disparity.value(), 10.0);
  EXPECT_DOUBLE_EQ(FindGt(frame, 3)->disparity.value(), 2.5);
}

// Left pixel (x, y) shows the same surface point as right pixel (x - d, y); with noise off and
// integer disparities, their colours must be equal wherever both see the same surface.
void ExpectStereoConsistent(double texture) {
  Scene scene = BaseScene();
  scene.background.texture = texture;
  scene.objects = {Box(1, 20, 20, 2.0, 21.3, 15.7, {30, 180, 60}),
                   Box(2, 44, 36, 1.0, 17, 13, {40, 60, 200})};
  scene.objects[1].shape = SynthShape::kBlob;
  for (SceneObject& o : scene.objects) {
    o.texture = texture;
    o.texture_cell_m = 0.05;
  }
  const RenderedFrame frame = SceneRenderer(scene).Render(4);
  int compared = 0;
  for (int y = 0; y < scene.height; ++y) {
    for (int x = 0; x < scene.width; ++x) {
      const int d = static_cast<int>(frame.disparity.at<float>(y, x));
      ASSERT_EQ(d, frame.disparity.at<float>(y, x));
      const int xr = x - d;
      if (xr < 0 || frame.right_ids.at<int>(y, xr) != frame.left_ids.at<int>(y, x)) continue;
      ASSERT_EQ(frame.left.at<cv::Vec3b>(y, x), frame.right.at<cv::Vec3b>(y, xr))
          << "texture " << texture << " left " << x << "," << y;
      ++compared;
    }
  }
  EXPECT_GT(compared, scene.width * scene.height * 8 / 10);
  // Each object appears in the right view shifted left by its disparity.
  for (const auto& [id, d] : std::vector<std::pair<int, int>>{{1, 5}, {2, 10}}) {
    const cv::Rect left = BoxOfId(frame.left_ids, id);
    const cv::Rect right = BoxOfId(frame.right_ids, id);
    ASSERT_GT(left.area(), 0);
    EXPECT_EQ(right, left - cv::Point(d, 0)) << "object " << id;
  }
  if (texture > 0) {
    // The texture is really there: the background is not uniform.
    cv::Scalar mean, stddev;
    cv::meanStdDev(frame.left, mean, stddev, frame.left_ids == 0);
    EXPECT_GT(stddev[0], 2.0);
  }
}

TEST(SceneRenderer, StereoViewsAgreeUntextured) { ExpectStereoConsistent(0.0); }

TEST(SceneRenderer, StereoViewsAgreeTextured) { ExpectStereoConsistent(25.0); }

TEST(SceneRenderer, FullyHiddenObjectHasZeroFractionAndEmptyBox) {
  Scene scene = BaseScene();
  scene.objects = {Box(1, 30, 24, 1.0, 40, 30), Box(2, 30, 24, 3.0, 6, 6)};
  const RenderedFrame frame = SceneRenderer(scene).Render(0);
  const GtObject* hidden = FindGt(frame, 2);
  ASSERT_NE(hidden, nullptr);
  EXPECT_EQ(hidden->visible_fraction, 0.0);
  EXPECT_EQ(hidden->box, cv::Rect2d(0, 0, 0, 0));
  EXPECT_EQ(cv::countNonZero(frame.left_ids == 2), 0);
  EXPECT_DOUBLE_EQ(hidden->disparity.value(), kFocal * kBaseline / 3.0);
  const GtObject* front = FindGt(frame, 1);
  EXPECT_EQ(front->visible_fraction, 1.0);
  EXPECT_EQ(front->box, cv::Rect2d(10, 9, 40, 30));
}

TEST(SceneRenderer, HalfOutOfTheImageHasFractionOneHalf) {
  Scene scene = BaseScene();
  // Pixel centres are at integer coordinates, so the image's left edge is x = -0.5.
  scene.objects = {Box(1, -0.5, 24, 2.0, 20, 10), Box(2, 31.5, 47.5, 2.0, 16, 12)};
  scene.objects[1].shape = SynthShape::kEllipse;
  const RenderedFrame frame = SceneRenderer(scene).Render(0);
  EXPECT_DOUBLE_EQ(FindGt(frame, 1)->visible_fraction, 0.5);
  EXPECT_EQ(FindGt(frame, 1)->box, cv::Rect2d(0, 19, 10, 10));
  EXPECT_NEAR(FindGt(frame, 2)->visible_fraction, 0.5, 0.05);
  // Fully outside: present but invisible.
  scene.objects = {Box(1, -40, 24, 2.0, 20, 10)};
  const RenderedFrame outside = SceneRenderer(scene).Render(0);
  EXPECT_EQ(FindGt(outside, 1)->visible_fraction, 0.0);
}

TEST(SceneRenderer, ObjectMuchLargerThanTheImageCoversItAndCountsItsArea) {
  Scene scene = BaseScene();
  scene.objects = {Box(1, 32, 24, 0.05, 6400, 4000)};  // 6400 x 4000 px: its area is counted
  const RenderedFrame frame = SceneRenderer(scene).Render(0);
  const GtObject* gt = FindGt(frame, 1);
  EXPECT_EQ(gt->box, cv::Rect2d(0, 0, 64, 48));
  EXPECT_NEAR(gt->visible_fraction, 64.0 * 48.0 / (6400.0 * 4000.0), 1e-12);
  EXPECT_DOUBLE_EQ(gt->disparity.value(), 200.0);
}

TEST(SceneRenderer, GroundTruthBoxesAreTheBoundingBoxesOfTheIdMap) {
  Scene scene = BaseScene();
  scene.objects = {Box(1, 20, 20, 2.0, 20, 16), Box(2, 28, 24, 1.0, 14, 14),
                   Box(3, 60, 40, 3.0, 18, 18)};
  scene.objects[1].shape = SynthShape::kTriangle;
  scene.objects[2].shape = SynthShape::kBlob;
  const RenderedFrame frame = SceneRenderer(scene).Render(2);
  ASSERT_EQ(frame.objects.size(), 3u);
  for (const GtObject& gt : frame.objects) {
    const cv::Rect box = BoxOfId(frame.left_ids, gt.id);
    EXPECT_EQ(gt.box, cv::Rect2d(box)) << gt.id;
    EXPECT_GT(gt.visible_fraction, 0.0);
    EXPECT_LE(gt.visible_fraction, 1.0);
  }
  EXPECT_LT(FindGt(frame, 1)->visible_fraction, 1.0);  // partly behind object 2
  EXPECT_LT(FindGt(frame, 3)->visible_fraction, 1.0);  // partly outside the image
}

TEST(SceneRenderer, ApproachingObjectGrows) {
  Scene scene = BaseScene();
  SceneObject o = Box(1, 32, 24, 4.0, 8, 6);
  o.path.push_back({9, 32, 24, 1.0});
  scene.objects = {o};
  const SceneRenderer renderer(scene);
  double previous_width = 0.0;
  for (int frame = 0; frame <= 9; ++frame) {
    // The frame is kept: FindGt points into its objects, which a temporary would free at the
    // end of this statement.
    const RenderedFrame rendered = renderer.Render(frame);
    const GtObject* gt = FindGt(rendered, 1);
    ASSERT_NE(gt, nullptr) << frame;
    const double depth = 4.0 - frame / 3.0;
    EXPECT_GE(gt->box.width, previous_width) << frame;
    EXPECT_NEAR(gt->box.width, 8.0 * 4.0 / depth, 1.0) << frame;  // f * size / Z
    previous_width = gt->box.width;
    EXPECT_NEAR(gt->disparity.value(), kFocal * kBaseline / depth, 1e-9);
  }
  EXPECT_EQ(previous_width, 32.0);  // four times the width at a quarter of the depth
}

TEST(SceneRenderer, BrightnessKeyframesScaleColours) {
  Scene scene = BaseScene();
  scene.objects = {Box(1, 32, 24, 2.0, 20, 20, {200, 100, 40})};
  scene.brightness = {{0, 1.0}, {10, 0.5}};
  const SceneRenderer renderer(scene);
  const RenderedFrame first = renderer.Render(0);
  EXPECT_EQ(first.left.at<cv::Vec3b>(24, 32), cv::Vec3b(40, 100, 200));  // BGR
  const RenderedFrame middle = renderer.Render(5);                       // gain 0.75
  EXPECT_EQ(middle.left.at<cv::Vec3b>(24, 32), cv::Vec3b(30, 75, 150));
  EXPECT_EQ(middle.right.at<cv::Vec3b>(24, 32 - 5), cv::Vec3b(30, 75, 150));
  EXPECT_EQ(middle.left.at<cv::Vec3b>(2, 2), cv::Vec3b(90, 90, 90));
  EXPECT_EQ(renderer.Render(20).left.at<cv::Vec3b>(2, 2), cv::Vec3b(60, 60, 60));
}

TEST(SceneRenderer, IsDeterministicAndTheSeedMatters) {
  Scene scene = BaseScene();
  scene.noise_left = scene.noise_right = 3.0;
  scene.background.texture = 20;
  scene.objects = {Box(1, 20, 20, 2.0, 20, 16)};
  scene.objects[0].texture = 15;
  const SceneRenderer a(scene);
  const SceneRenderer b(scene);
  a.Render(1);  // rendering another frame first changes nothing
  const RenderedFrame fa = a.Render(3);
  const RenderedFrame fb = b.Render(3);
  EXPECT_EQ(cv::norm(fa.left, fb.left, cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(fa.right, fb.right, cv::NORM_INF), 0.0);
  scene.seed = 4;
  const RenderedFrame fc = SceneRenderer(scene).Render(3);
  EXPECT_GT(cv::norm(fa.left, fc.left, cv::NORM_L1), 0.0);
  EXPECT_EQ(cv::norm(fa.left_ids, fc.left_ids, cv::NORM_INF), 0.0);  // geometry is not random
}

TEST(SceneRenderer, NoiseHasTheRequestedSigmaAndIsIndependentPerView) {
  Scene scene = BaseScene();
  scene.width = 200;
  scene.height = 150;
  scene.noise_left = 5.0;
  scene.noise_right = 2.0;
  const RenderedFrame frame = SceneRenderer(scene).Render(0);
  cv::Scalar mean, stddev;
  cv::meanStdDev(frame.left, mean, stddev);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(mean[c], 120.0, 0.2);
    // Rounding to integers adds a variance of 1/12.
    EXPECT_NEAR(stddev[c], std::sqrt(25.0 + 1.0 / 12), 0.15);
  }
  cv::meanStdDev(frame.right, mean, stddev);
  EXPECT_NEAR(stddev[0], std::sqrt(4.0 + 1.0 / 12), 0.1);
  // The views' noise is uncorrelated (the background is uniform, so equal pixels come only
  // from noise that happens to agree).
  cv::Mat left, right;
  frame.left.convertTo(left, CV_64F, 1, -120);
  frame.right.convertTo(right, CV_64F, 1, -120);
  const double correlation = left.dot(right) / std::sqrt(left.dot(left) * right.dot(right));
  EXPECT_LT(std::abs(correlation), 0.02);
}

TEST(SceneRenderer, ObjectsExistOnlyBetweenEntryAndExit) {
  Scene scene = BaseScene();
  scene.objects = {Box(1, 32, 24, 2.0, 10, 10)};
  scene.objects[0].entry = 3;
  scene.objects[0].exit = 5;
  const SceneRenderer renderer(scene);
  for (int frame = 0; frame < 8; ++frame) {
    const RenderedFrame rendered = renderer.Render(frame);
    const bool present = frame >= 3 && frame <= 5;
    EXPECT_EQ(rendered.objects.size(), present ? 1u : 0u) << frame;
    EXPECT_EQ(cv::countNonZero(rendered.left_ids == 1), present ? 100 : 0) << frame;
  }
}

TEST(SceneRenderer, OscillationMovesTheObjectSinusoidally) {
  Scene scene = BaseScene();
  scene.objects = {Box(1, 32, 24, 2.0, 10, 10)};
  scene.objects[0].oscillation = {8.0, -4.0, 8.0, 0.0};
  const SceneRenderer renderer(scene);
  EXPECT_EQ(FindGt(renderer.Render(0), 1)->box, cv::Rect2d(27, 19, 10, 10));
  EXPECT_EQ(FindGt(renderer.Render(2), 1)->box, cv::Rect2d(35, 15, 10, 10));  // a quarter period
  EXPECT_EQ(FindGt(renderer.Render(6), 1)->box, cv::Rect2d(19, 23, 10, 10));
}

TEST(SceneRenderer, ShapesCoverTheirArea) {
  Scene scene = BaseScene();
  scene.width = 160;
  scene.height = 120;
  scene.objects = {Box(1, 40, 60, 2.0, 60, 60), Box(2, 120, 60, 2.0, 60, 60)};
  scene.objects[0].shape = SynthShape::kEllipse;
  scene.objects[1].shape = SynthShape::kTriangle;
  const RenderedFrame frame = SceneRenderer(scene).Render(0);
  EXPECT_NEAR(cv::countNonZero(frame.left_ids == 1), 3.14159265 * 30 * 30, 30);
  // The triangle has its apex at the top (y = 30) and its 60 px base at the bottom (y < 90):
  // each row is as wide as its distance below the apex.
  for (int y = 28; y <= 92; ++y) {
    const int expected = (y >= 30 && y < 90) ? y - 30 : 0;
    EXPECT_NEAR(cv::countNonZero(frame.left_ids.row(y) == 2), expected, 1) << "row " << y;
  }
}

TEST(SceneRenderer, BlobDeformsOverTime) {
  Scene scene = BaseScene();
  scene.width = 120;
  scene.height = 120;
  scene.objects = {Box(1, 60, 60, 2.0, 60, 60)};
  scene.objects[0].shape = SynthShape::kBlob;
  scene.objects[0].blob = {5, 0.3, 20.0};
  const SceneRenderer renderer(scene);
  const cv::Mat at0 = renderer.Render(0).left_ids == 1;
  const cv::Mat at5 = renderer.Render(5).left_ids == 1;
  const int area = cv::countNonZero(at0);
  // The mean of the radius deformation is zero, so the area stays near the base circle's
  // (a little above it: the area grows with the square of the radius).
  EXPECT_NEAR(area, 3.14159265 * 30 * 30, 0.15 * 3.14159265 * 30 * 30);
  cv::Mat changed;
  cv::bitwise_xor(at0, at5, changed);
  EXPECT_GT(cv::countNonZero(changed), area / 10);
  const cv::Rect box = cv::boundingRect(at0);
  EXPECT_LE(box.width, 1.3 * 60 + 1);
  EXPECT_GT(box.width, 0.7 * 60);
}

}  // namespace
}  // namespace attend
