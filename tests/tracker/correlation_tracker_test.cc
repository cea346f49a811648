// The correlation mode of the bip tracker (tracker/correlation_tracker.h) and its parts, on
// drawn frames whose true boxes are known: its features, its filters, following a translating
// and a growing target, an occlusion, re-detection after a jump, losing a target, and its mask.
#include "tracker/correlation_tracker.h"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgproc.hpp>

#include "tracker/correlation_filter.h"
#include "tracker/hog_features.h"
#include "util/error.h"

namespace attend {
namespace {

using tracker_internal::HogCells;
using tracker_internal::kHogChannels;
using tracker_internal::ResponsePeak;
using tracker_internal::ScaleFilter;
using tracker_internal::TranslationFilter;

const cv::Size kFrame(320, 240);

cv::Mat NoiseBackground(int seed = 7) {
  cv::Mat image(kFrame, CV_8UC3);
  cv::RNG(seed).fill(image, cv::RNG::UNIFORM, 60, 150);
  cv::GaussianBlur(image, image, cv::Size(5, 5), 1.5);
  return image;
}

// A textured patch of `size`: a coloured checker with noise of its own.
cv::Mat Texture(cv::Size size) {
  cv::Mat texture(size, CV_8UC3);
  cv::RNG rng(11);
  for (int y = 0; y < size.height; ++y) {
    for (int x = 0; x < size.width; ++x) {
      const int cell = std::max(3, size.width / 6);
      const bool dark = ((x / cell) + (y / cell)) % 2 == 0;
      const cv::Vec3b base = dark ? cv::Vec3b(40, 60, 200) : cv::Vec3b(220, 200, 40);
      cv::Vec3b pixel;
      for (int k = 0; k < 3; ++k) pixel[k] = cv::saturate_cast<uchar>(base[k] + rng.uniform(-15, 16));
      texture.at<cv::Vec3b>(y, x) = pixel;
    }
  }
  return texture;
}

cv::Mat Draw(const cv::Rect& box, int seed = 7) {
  cv::Mat image = NoiseBackground(seed);
  cv::Mat texture;
  cv::resize(Texture(cv::Size(48, 48)), texture, box.size(), 0, 0, cv::INTER_LINEAR);
  texture.copyTo(image(box));
  return image;
}

double Iou(const cv::Rect& a, const cv::Rect& b) {
  const double inter = (a & b).area();
  return inter / (a.area() + b.area() - inter);
}

std::unique_ptr<TargetTracker> MakeTracker(CorrelationOptions options = {}) {
  TargetTrackerOptions tracker;
  tracker.bip.mode = TrackerMode::kCorrelation;
  tracker.correlation = options;
  return TargetTracker::Create(tracker);
}

TEST(HogCells, AVerticalEdgeVotesForTheHorizontalGradient) {
  cv::Mat patch(32, 32, CV_8UC3, cv::Scalar(20, 20, 20));
  patch(cv::Rect(16, 0, 16, 32)).setTo(cv::Scalar(220, 220, 220));
  HogCells hog;
  std::vector<cv::Mat> channels;
  hog.Compute(patch, 4, &channels);
  ASSERT_EQ(channels.size(), static_cast<size_t>(kHogChannels));
  ASSERT_EQ(channels[0].size(), cv::Size(8, 8));
  // Cells 3 and 4 of each row hold the edge: signed bin 0 (gradient towards +x) is their
  // strongest orientation channel, bin 9 (towards -x) is empty.
  for (int r = 0; r < 8; ++r) {
    for (int o = 1; o < 18; ++o) EXPECT_GE(channels[0].at<float>(r, 4), channels[o].at<float>(r, 4));
    EXPECT_GT(channels[0].at<float>(r, 4), 0.1f);
    EXPECT_EQ(channels[9].at<float>(r, 4), 0.f);
    // Far from the edge there is no gradient.
    EXPECT_EQ(channels[0].at<float>(r, 0), 0.f);
  }
  // The intensity channel: dark left, bright right.
  EXPECT_LT(channels[kHogChannels - 1].at<float>(0, 0), -0.3f);
  EXPECT_GT(channels[kHogChannels - 1].at<float>(0, 7), 0.3f);
}

TEST(TranslationFilter, FindsACircularShiftOfWhatItLearnt) {
  const cv::Size cells(24, 20);
  std::vector<cv::Mat> channels(3);
  cv::RNG rng(3);
  for (cv::Mat& channel : channels) {
    channel.create(cells, CV_32F);
    rng.fill(channel, cv::RNG::UNIFORM, 0.f, 1.f);
    cv::GaussianBlur(channel, channel, cv::Size(3, 3), 0.8);
  }
  TranslationFilter filter(cells, 1.0, 1e-3);
  filter.Learn(channels, 1.0);
  double peak = 0.0;
  // The same features: the peak at the centre.
  cv::Point2d at = ResponsePeak(filter.Respond(channels), &peak);
  EXPECT_NEAR(at.x, cells.width / 2, 0.3);
  EXPECT_NEAR(at.y, cells.height / 2, 0.3);
  EXPECT_GT(peak, 0.5);
  // Content moved 3 cells right and 2 up (away from the window's edges, where the cosine
  // window hides it): the peak moves with it.
  std::vector<cv::Mat> shifted(3);
  for (size_t l = 0; l < channels.size(); ++l) {
    const cv::Mat m = (cv::Mat_<double>(2, 3) << 1, 0, 3, 0, 1, -2);
    cv::warpAffine(channels[l], shifted[l], m, cells, cv::INTER_NEAREST, cv::BORDER_WRAP);
  }
  at = ResponsePeak(filter.Respond(shifted), &peak);
  EXPECT_NEAR(at.x, cells.width / 2 + 3, 0.5);
  EXPECT_NEAR(at.y, cells.height / 2 - 2, 0.5);
}

TEST(ScaleFilter, PeaksAtTheMiddleForWhatItLearntAndFollowsAShift) {
  constexpr int kScales = 15;
  cv::Mat samples(40, kScales, CV_32F);
  cv::RNG(5).fill(samples, cv::RNG::UNIFORM, 0.f, 1.f);
  cv::GaussianBlur(samples, samples, cv::Size(5, 1), 1.5);
  ScaleFilter filter(kScales, std::sqrt(kScales) / 4.0, 1e-2);
  filter.Learn(samples, 1.0);
  EXPECT_NEAR(filter.BestSample(samples), kScales / 2, 0.3);
  // Columns moved one to the right: the best sample is one to the right.
  cv::Mat shifted = samples.clone();
  for (int n = 1; n < kScales; ++n) samples.col(n - 1).copyTo(shifted.col(n));
  EXPECT_NEAR(filter.BestSample(shifted), kScales / 2 + 1, 0.5);
}

TEST(CorrelationTracker, AStillTargetStaysWhereItIs) {
  const cv::Rect box(140, 100, 40, 40);
  const cv::Mat frame = Draw(box);
  auto tracker = MakeTracker();
  ASSERT_EQ(tracker->StartFromBox(frame, box), 1);
  for (int f = 0; f < 20; ++f) {
    std::vector<TrackResult> results;
    tracker->Track(frame, &results);
    ASSERT_EQ(results.size(), 1u);
    EXPECT_EQ(results[0].state, TrackState::kFound);
    EXPECT_LE(std::abs(results[0].box.x - box.x), 1) << "frame " << f;
    EXPECT_LE(std::abs(results[0].box.y - box.y), 1) << "frame " << f;
    EXPECT_LE(std::abs(results[0].box.width - box.width), 2) << "frame " << f;
  }
}

TEST(CorrelationTracker, FollowsATranslatingTarget) {
  auto box_at = [](int f) { return cv::Rect(40 + 5 * f, 60 + 2 * f, 40, 40); };
  auto tracker = MakeTracker();
  ASSERT_EQ(tracker->StartFromBox(Draw(box_at(0)), box_at(0)), 1);
  for (int f = 1; f < 40; ++f) {
    std::vector<TrackResult> results;
    tracker->Track(Draw(box_at(f)), &results);
    ASSERT_EQ(results.size(), 1u);
    EXPECT_EQ(results[0].state, TrackState::kFound) << "frame " << f;
    EXPECT_GT(Iou(results[0].box, box_at(f)), 0.8) << "frame " << f;
  }
}

TEST(CorrelationTracker, FollowsAGrowingTargetInSize) {
  // The target grows from 40 to about 72 px a side over 30 frames (2 % a frame).
  auto box_at = [](int f) {
    const int side = static_cast<int>(std::lround(40 * std::pow(1.02, f)));
    return cv::Rect(160 - side / 2, 120 - side / 2, side, side);
  };
  auto tracker = MakeTracker();
  ASSERT_EQ(tracker->StartFromBox(Draw(box_at(0)), box_at(0)), 1);
  std::vector<TrackResult> results;
  for (int f = 1; f <= 30; ++f) {
    results.clear();
    tracker->Track(Draw(box_at(f)), &results);
  }
  ASSERT_EQ(results.size(), 1u);
  EXPECT_NEAR(results[0].box.width, box_at(30).width, 0.1 * box_at(30).width);
  EXPECT_GT(Iou(results[0].box, box_at(30)), 0.75);
}

TEST(CorrelationTracker, AnOccludedTargetIsNotFoundThenFoundAgain) {
  const cv::Rect box(140, 100, 40, 40);
  // The panel's window responds at about half of the target's usual peak (the noise at its
  // border, and the colour model's share): a bar of 0.7 tells it from the target.
  CorrelationOptions options;
  options.confidence_ratio = 0.7f;
  auto tracker = MakeTracker(options);
  ASSERT_EQ(tracker->StartFromBox(Draw(box), box), 1);
  std::vector<TrackResult> results;
  for (int f = 0; f < 10; ++f) {
    results.clear();
    tracker->Track(Draw(box), &results);
  }
  // Hidden behind a grey panel for 5 frames.
  for (int f = 0; f < 5; ++f) {
    cv::Mat frame = Draw(box);
    frame(cv::Rect(120, 80, 80, 80)).setTo(cv::Scalar(128, 128, 128));
    results.clear();
    tracker->Track(frame, &results);
    ASSERT_EQ(results.size(), 1u);
    EXPECT_EQ(results[0].state, TrackState::kOccluded) << "hidden frame " << f;
    EXPECT_EQ(results[0].box, box) << "kept at its last box";
  }
  results.clear();
  tracker->Track(Draw(box), &results);
  ASSERT_EQ(results.size(), 1u);
  EXPECT_EQ(results[0].state, TrackState::kFound);
  EXPECT_GT(Iou(results[0].box, box), 0.8);
}

TEST(CorrelationTracker, ATargetThatJumpsIsFoundByTheWiderSearch) {
  const cv::Rect before(60, 100, 40, 40), after(150, 100, 40, 40);
  CorrelationOptions options;
  options.redetect_windows = 2;
  auto tracker = MakeTracker(options);
  ASSERT_EQ(tracker->StartFromBox(Draw(before), before), 1);
  std::vector<TrackResult> results;
  for (int f = 0; f < 10; ++f) {
    results.clear();
    tracker->Track(Draw(before), &results);
  }
  // 90 px in one frame: beyond the window (40 + 40 px), within two half windows.
  for (int f = 0; f < 3; ++f) {
    results.clear();
    tracker->Track(Draw(after), &results);
  }
  ASSERT_EQ(results.size(), 1u);
  EXPECT_EQ(results[0].state, TrackState::kFound);
  EXPECT_GT(Iou(results[0].box, after), 0.8);
  // Without the wider search it stays where it was, not found.
  options.redetect_windows = 0;
  auto plain = MakeTracker(options);
  ASSERT_EQ(plain->StartFromBox(Draw(before), before), 1);
  for (int f = 0; f < 10; ++f) {
    results.clear();
    plain->Track(Draw(before), &results);
  }
  results.clear();
  plain->Track(Draw(after), &results);
  EXPECT_NE(results[0].state, TrackState::kFound);
  EXPECT_LT(Iou(results[0].box, after), 0.1);
}

TEST(CorrelationTracker, ATargetGoneForMissedFramesIsLostAndRemoved) {
  const cv::Rect box(140, 100, 40, 40);
  CorrelationOptions options;
  options.missed_frames = 4;
  options.confidence_ratio = 0.5f;
  auto tracker = MakeTracker(options);
  ASSERT_EQ(tracker->StartFromBox(Draw(box), box), 1);
  std::vector<TrackResult> results;
  for (int f = 0; f < 5; ++f) {
    results.clear();
    tracker->Track(Draw(box), &results);
  }
  const cv::Mat empty = NoiseBackground();
  for (int f = 1; f <= 4; ++f) {
    results.clear();
    tracker->Track(empty, &results);
    ASSERT_EQ(results.size(), 1u);
    EXPECT_EQ(results[0].state, f < 4 ? TrackState::kOccluded : TrackState::kLost) << f;
  }
  EXPECT_TRUE(tracker->ids().empty());
}

TEST(CorrelationTracker, TheMaskIsTheTargetsRegionsNotTheBackground) {
  // A uniform red disc on a uniform blue background: its box's corners are background.
  cv::Mat frame(kFrame, CV_8UC3, cv::Scalar(200, 60, 30));
  cv::circle(frame, cv::Point(160, 120), 30, cv::Scalar(30, 40, 220), cv::FILLED);
  const cv::Rect box(130, 90, 61, 61);
  auto tracker = MakeTracker();
  ASSERT_EQ(tracker->StartFromBox(frame, box), 1);
  std::vector<TrackResult> results;
  tracker->Track(frame, &results);
  const cv::Mat mask = tracker->Mask(1);
  ASSERT_EQ(mask.size(), frame.size());
  cv::Mat disc(kFrame, CV_8UC1, cv::Scalar(0));
  cv::circle(disc, cv::Point(160, 120), 30, cv::Scalar(255), cv::FILLED);
  const double inter = cv::countNonZero(mask & disc);
  const double uni = cv::countNonZero(mask | disc);
  EXPECT_GT(inter / uni, 0.9);
  // With mask_likelihood 0 the mask is the box.
  CorrelationOptions options;
  options.mask_likelihood = 0.f;
  auto boxes = MakeTracker(options);
  ASSERT_EQ(boxes->StartFromBox(frame, box), 1);
  results.clear();
  boxes->Track(frame, &results);
  EXPECT_EQ(cv::countNonZero(boxes->Mask(1)), results[0].box.area());
}

TEST(CorrelationTracker, BadOptionsAreRefusedByName) {
  TargetTrackerOptions options;
  options.bip.mode = TrackerMode::kCorrelation;
  options.correlation.scales = 16;
  EXPECT_NE(options.Check().find("scales"), std::string::npos);
  EXPECT_THROW(TargetTracker::Create(options), ConfigError);
  options.correlation.scales = 15;
  options.correlation.colour_share = 2.f;
  EXPECT_NE(options.Check().find("colour_share"), std::string::npos);
}

}  // namespace
}  // namespace attend
