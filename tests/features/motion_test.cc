#include "features/motion.h"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>
#include <random>

#include "features/lazy_frame_context.h"
#include "util/error.h"
#include "features/builtin.h"
#include "tests/support/temp_dir.h"

namespace attend {
namespace {

// A textured wall (smooth stripes 60..180) with a bright square at `square_x`, plus Gaussian
// sensor noise of `noise` grey levels, then the light: value * gain + offset.
cv::Mat Scene(int square_x, double noise, uint32_t seed, double gain = 1.0, double offset = 0.0) {
  cv::Mat grey(120, 160, CV_32F);
  for (int y = 0; y < grey.rows; ++y) {
    for (int x = 0; x < grey.cols; ++x) {
      grey.at<float>(y, x) = 120.f + 60.f * std::sin(x * 0.15f) * std::cos(y * 0.11f);
    }
  }
  if (square_x >= 0) grey(cv::Rect(square_x, 50, 20, 20)).setTo(220.f);
  std::mt19937 random(seed);
  std::normal_distribution<float> gauss(0.f, static_cast<float>(noise));
  for (int y = 0; y < grey.rows; ++y) {
    for (int x = 0; x < grey.cols; ++x) {
      float& v = grey.at<float>(y, x);
      v = static_cast<float>((v + gauss(random)) * gain + offset);
    }
  }
  cv::Mat grey8, bgr;
  grey.convertTo(grey8, CV_8U);  // saturates
  cv::cvtColor(grey8, bgr, cv::COLOR_GRAY2BGR);
  return bgr;
}

double MaxOf(const cv::Mat& map) {
  double max = 0.0;
  cv::minMaxLoc(map, nullptr, &max);
  return max;
}

TEST(MotionOptions, DefaultsAreValid) { EXPECT_EQ(MotionOptions().Check(), ""); }

TEST(MotionOptions, CheckNamesTheField) {
  MotionOptions options;
  options.window = 4;
  EXPECT_NE(options.Check().find("window"), std::string::npos);
  options = MotionOptions();
  options.rate = 0.0;
  EXPECT_NE(options.Check().find("rate"), std::string::npos);
}

TEST(MotionDetector, FirstFrameIsZero) {
  MotionDetector detector{MotionOptions()};
  cv::Mat map;
  detector.Compute(0, Scene(30, 3.0, 1), nullptr, &map);
  ASSERT_EQ(map.type(), CV_32FC1);
  ASSERT_EQ(map.size(), cv::Size(160, 120));
  EXPECT_EQ(cv::countNonZero(map), 0);
}

TEST(MotionDetector, StillNoisySceneGivesNothing) {
  MotionDetector detector{MotionOptions()};
  cv::Mat map;
  detector.Compute(0, Scene(30, 4.0, 1), nullptr, &map);
  for (int t = 1; t < 5; ++t) {
    detector.Compute(t, Scene(30, 4.0, 1 + t), nullptr, &map);
    EXPECT_EQ(cv::countNonZero(map), 0) << "frame " << t;
    // Noise of sigma 4, smoothed by the Gaussian of 1.5 px and differenced: well below 4.
    EXPECT_GT(detector.last_noise(), 0.3);
    EXPECT_LT(detector.last_noise(), 4.0);
  }
}

TEST(MotionDetector, MovingSquareLightsUpWhereItWasAndIs) {
  MotionDetector detector{MotionOptions()};
  cv::Mat map;
  detector.Compute(0, Scene(30, 3.0, 1), nullptr, &map);
  detector.Compute(1, Scene(42, 3.0, 2), nullptr, &map);
  // The square moved 12 px right: its leading (x 50..61) and trailing (x 30..41) parts changed.
  const cv::Rect changed(30, 50, 32, 20);
  cv::Point peak;
  cv::minMaxLoc(map, nullptr, nullptr, nullptr, &peak);
  EXPECT_TRUE(changed.contains(peak)) << peak;
  EXPECT_GT(cv::mean(map(cv::Rect(52, 52, 8, 16)))[0], 30.0);
  EXPECT_GT(cv::mean(map(cv::Rect(31, 52, 8, 16)))[0], 30.0);
  // Far from it nothing: the window (9 px) and blur spread the change by a few pixels only.
  cv::Mat far = cv::Mat::ones(map.size(), CV_8U);
  far(cv::Rect(changed.x - 8, changed.y - 8, changed.width + 16, changed.height + 16)).setTo(0);
  cv::Mat outside;
  map.copyTo(outside, far);
  EXPECT_EQ(MaxOf(outside), 0.0);
}

TEST(MotionDetector, GlobalBrightnessChangeIsNotMotion) {
  MotionDetector detector{MotionOptions()};
  cv::Mat map;
  detector.Compute(0, Scene(30, 2.0, 1), nullptr, &map);
  // The light gets 10 % brighter and 8 grey levels brighter still (nothing saturates: 220 x
  // 1.1 + 8 = 250): no pixel moved.
  detector.Compute(1, Scene(30, 2.0, 2, 1.1, 8.0), nullptr, &map);
  EXPECT_NEAR(detector.last_gain(), 1.1, 0.02);
  EXPECT_NEAR(detector.last_offset(), 8.0, 2.5);
  EXPECT_EQ(MaxOf(map), 0.0);
  // And with the square moving while the light changes back, only the square shows.
  detector.Compute(2, Scene(42, 2.0, 3), nullptr, &map);
  cv::Point peak;
  cv::minMaxLoc(map, nullptr, nullptr, nullptr, &peak);
  EXPECT_TRUE(cv::Rect(30, 50, 32, 20).contains(peak)) << peak;
  EXPECT_EQ(MaxOf(map(cv::Rect(100, 0, 60, 120))), 0.0);
}

TEST(MotionDetector, PlainDifferenceWouldSeeTheBrightnessChange) {
  // The counter-test of the one above: without the fit, the same frames differ by 20 levels.
  const cv::Mat a = Scene(30, 2.0, 1), b = Scene(30, 2.0, 2, 1.1, 8.0);
  cv::Mat difference;
  cv::absdiff(a, b, difference);
  EXPECT_GT(cv::mean(difference)[0], 15.0);  // 0.1 x 120 + 8 on average, twice min_change
}

TEST(MotionDetector, RestartsWhenTheSequenceBreaks) {
  MotionDetector detector{MotionOptions()};
  cv::Mat map;
  detector.Compute(5, Scene(30, 1.0, 1), nullptr, &map);
  detector.Compute(6, Scene(60, 1.0, 2), nullptr, &map);
  ASSERT_GT(MaxOf(map), 10.0);
  // A frame index that does not go up: a new sequence, compared with nothing.
  detector.Compute(0, Scene(90, 1.0, 3), nullptr, &map);
  EXPECT_EQ(MaxOf(map), 0.0);
  // The background is that frame now: the square moving from 90 shows at 90 and 110.
  detector.Compute(1, Scene(110, 1.0, 4), nullptr, &map);
  cv::Point peak;
  cv::minMaxLoc(map, nullptr, nullptr, nullptr, &peak);
  EXPECT_TRUE(cv::Rect(90, 50, 40, 20).contains(peak)) << peak;
  EXPECT_EQ(MaxOf(map(cv::Rect(0, 0, 80, 120))), 0.0);  // nothing of the earlier frames
  // Another image size: also a restart.
  cv::Mat small;
  cv::resize(Scene(30, 1.0, 5), small, cv::Size(80, 60));
  detector.Compute(2, small, nullptr, &map);
  EXPECT_EQ(map.size(), cv::Size(80, 60));
  EXPECT_EQ(MaxOf(map), 0.0);
}

TEST(MotionDetector, RunningBackgroundRemembersWhereTheSquareWas) {
  // rate 0.5: the background keeps half of the older frames, so a square that left x = 30
  // two frames ago still shows there; with rate 1 (previous frame) it does not.
  for (const double rate : {1.0, 0.5}) {
    MotionOptions options;
    options.rate = rate;
    MotionDetector detector(options);
    cv::Mat map;
    detector.Compute(0, Scene(30, 1.0, 1), nullptr, &map);
    detector.Compute(1, Scene(70, 1.0, 2), nullptr, &map);
    detector.Compute(2, Scene(110, 1.0, 3), nullptr, &map);
    const double old_place = cv::mean(map(cv::Rect(32, 52, 16, 16)))[0];
    if (rate == 1.0) {
      EXPECT_EQ(old_place, 0.0);
    } else {
      EXPECT_GT(old_place, 10.0);
    }
  }
}

TEST(MotionFeature, IsBuiltInAndReadsItsParameters) {
  const FeatureRegistry registry = BuiltinFeatures();
  ASSERT_NE(registry.Find("motion"), nullptr);
  FeatureSetup setup;
  setup.home = testing::ProjectRoot();
  FeatureSpec spec;
  spec.name = "motion";
  spec.params = ParamBlock::Parse("{window: 4}", "test.yaml");
  EXPECT_THROW(registry.Create(spec, setup), ConfigError);
  spec.params = ParamBlock::Parse("{rate: 0}", "test.yaml");
  EXPECT_THROW(registry.Create(spec, setup), ConfigError);
  spec.params = ParamBlock::Parse("{windw: 5}", "test.yaml");
  EXPECT_THROW(registry.Create(spec, setup), ConfigError);

  // Per region: the moved square's colour regions carry one value each, the wall none.
  spec.params = ParamBlock::Parse("{per_region: true, blur: 0}", "test.yaml");
  std::unique_ptr<FeatureMap> feature = registry.Create(spec, setup);
  LazyFrameContext context;
  cv::Mat map;
  const cv::Mat first = Scene(30, 0.0, 1), second = Scene(42, 0.0, 1);
  context.Reset(0, first);
  feature->Compute(context, &map);
  EXPECT_EQ(MaxOf(map), 0.0);
  context.Reset(1, second);
  feature->Compute(context, &map);
  EXPECT_GT(map.at<float>(60, 55), 10.f);  // the square's new part
  // The wall far away: at most the share of its region that the square uncovered.
  EXPECT_LT(map.at<float>(10, 140), 0.1f * map.at<float>(60, 55));
}

}  // namespace
}  // namespace attend
