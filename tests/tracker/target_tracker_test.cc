// The tracker interface (tracker/target_tracker.h): every kind on drawn frames whose true boxes
// are known, the OpenCV kinds' occluded -> lost rule and masks, and the bip kind against
// MultiTracker itself.
#include "tracker/target_tracker.h"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "eval/tracking_scores.h"
#include "util/error.h"

namespace attend {
namespace {

const cv::Size kSize(200, 150);
constexpr int kSide = 36;

// A background of fine fixed noise; the textured square (a coarse checker with its own noise)
// translates 3 px right and 1 px down a frame.
cv::Rect SquareBox(int frame) { return {30 + 3 * frame, 40 + frame, kSide, kSide}; }

cv::Mat Background() {
  cv::Mat image(kSize, CV_8UC3);
  cv::RNG(7).fill(image, cv::RNG::UNIFORM, 90, 130);
  return image;
}

cv::Mat Texture() {
  cv::Mat texture(kSide, kSide, CV_8UC3);
  for (int y = 0; y < kSide; ++y) {
    for (int x = 0; x < kSide; ++x) {
      const bool dark = ((x / 6) + (y / 6)) % 2 == 0;
      texture.at<cv::Vec3b>(y, x) = dark ? cv::Vec3b(30, 40, 160) : cv::Vec3b(210, 220, 60);
    }
  }
  return texture;
}

// Frame f with the square drawn when `visible`.
cv::Mat Scene(int frame, bool visible = true) {
  cv::Mat image = Background();
  if (visible) Texture().copyTo(image(SquareBox(frame)));
  return image;
}

double Iou(const cv::Rect& a, const cv::Rect& b) {
  return ScoreTracking({cv::Rect2d(a)}, {cv::Rect2d(b)}).mean_iou;
}

std::unique_ptr<TargetTracker> Make(TrackerKind kind, int lost_frames = 10) {
  TargetTrackerOptions options;
  options.kind = kind;
  options.opencv.lost_frames = lost_frames;
  return TargetTracker::Create(options);
}

TEST(TargetTracker, DefaultsAreValid) {
  EXPECT_EQ(TargetTrackerOptions().Check(), "");
  EXPECT_EQ(OpenCvTrackerOptions().Check(), "");
  EXPECT_EQ(TargetTrackerOptions().kind, TrackerKind::kBip);
}

TEST(TargetTracker, KindNamesRoundTrip) {
  ASSERT_EQ(TrackerKindNames().size(), 3u);
  for (const std::string& name : TrackerKindNames()) {
    TrackerKind kind;
    ASSERT_TRUE(TrackerKindFromName(name, &kind)) << name;
    EXPECT_EQ(TrackerKindName(kind), name);
    EXPECT_EQ(Make(kind)->name(), name);
  }
  TrackerKind kind = TrackerKind::kKcf;
  EXPECT_FALSE(TrackerKindFromName("mosse", &kind));
  EXPECT_EQ(kind, TrackerKind::kKcf);
}

// The kinds' table: each row's factory makes its kind, every key of the two option blocks is
// read by some kind, and the bip kind reads exactly the BIP block.
TEST(TargetTracker, EachKindsRowMakesItAndEveryBlockKeyHasAKind) {
  for (const TrackerKindInfo& info : TrackerKinds()) {
    TargetTrackerOptions options;
    options.kind = info.kind;
    EXPECT_EQ(info.create(options, nullptr)->kind(), info.kind) << info.name;
    EXPECT_EQ(&TrackerKindOf(info.kind), &info);
  }
  const auto used = [](std::string_view key) {
    int kinds = 0;
    for (const TrackerKindInfo& info : TrackerKinds()) kinds += info.uses_key(key) ? 1 : 0;
    return kinds;
  };
  for (const OptionField<TrackerOptions>& field : TrackerOptions::Fields()) {
    if (!field.is_key) continue;
    EXPECT_EQ(used(field.name), 1) << field.name;
    EXPECT_TRUE(TrackerKindOf(TrackerKind::kBip).uses_key(field.name)) << field.name;
  }
  for (const OptionField<OpenCvTrackerOptions>& field : OpenCvTrackerOptions::Fields()) {
    EXPECT_GE(used(field.name), 1) << field.name;
    EXPECT_FALSE(TrackerKindOf(TrackerKind::kBip).uses_key(field.name)) << field.name;
  }
  EXPECT_FALSE(TrackerKindOf(TrackerKind::kCsrt).uses_key("kcf_detect_thresh"));
  EXPECT_STREQ(TrackerKindOf(TrackerKind::kBip).skin_similarity, "skin");
  EXPECT_STREQ(TrackerKindOf(TrackerKind::kKcf).colour_similarity, "appearance");
}

TEST(TargetTracker, InvalidOptionsOfTheChosenKindAreConfigErrors) {
  TargetTrackerOptions options;
  options.kind = TrackerKind::kCsrt;
  options.opencv.lost_frames = 0;
  EXPECT_NE(options.Check().find("lost_frames"), std::string::npos) << options.Check();
  EXPECT_THROW(TargetTracker::Create(options), ConfigError);
  // The BIP options are not the CSRT tracker's: not checked for it.
  options.opencv.lost_frames = 3;
  options.bip.alpha = -1.f;
  EXPECT_EQ(options.Check(), "");
  options.kind = TrackerKind::kBip;
  EXPECT_NE(options.Check().find("alpha"), std::string::npos) << options.Check();
}

// What the rows say beyond the class: the file attend track starts a kind from, why a start
// gave no target, and the settings its summary reports.
TEST(TargetTracker, EachKindsRowOwnsItsFileMessageAndSettings) {
  EXPECT_STREQ(TrackerKindOf(TrackerKind::kBip).config_file, "track.yaml");
  EXPECT_EQ(TrackerKindOf(TrackerKind::kKcf).config_file, nullptr);
  EXPECT_EQ(TrackerKindOf(TrackerKind::kCsrt).no_target, nullptr);
  EXPECT_NE(std::string(TrackerKindOf(TrackerKind::kBip).no_target).find("no target"),
            std::string::npos);
  TargetTrackerOptions options;
  options.bip.mode = TrackerMode::kThesis;
  options.bip.occlusion = true;
  const std::vector<TrackerSetting> settings = TrackerKindOf(TrackerKind::kBip).settings(options);
  ASSERT_EQ(settings.size(), 2u);
  EXPECT_EQ(settings[0].key, "mode");
  EXPECT_EQ(std::get<std::string>(settings[0].value), "thesis");
  EXPECT_EQ(settings[1].key, "occlusion");
  EXPECT_TRUE(std::get<bool>(settings[1].value));
  EXPECT_TRUE(TrackerKindOf(TrackerKind::kCsrt).settings(options).empty());
}

class EveryKind : public ::testing::TestWithParam<TrackerKind> {};

TEST_P(EveryKind, FollowsATranslatingTexturedSquare) {
  const std::unique_ptr<TargetTracker> tracker = Make(GetParam());
  const int id = tracker->StartFromBox(Scene(0), SquareBox(0));
  ASSERT_EQ(id, 1);
  EXPECT_EQ(tracker->ids(), std::vector<int>{1});
  std::vector<TrackResult> results;
  for (int f = 1; f < 25; ++f) {
    results.clear();
    tracker->Track(Scene(f), &results);
    ASSERT_EQ(results.size(), 1u) << "frame " << f;
    EXPECT_EQ(results[0].id, id);
    EXPECT_EQ(results[0].state, TrackState::kFound) << "frame " << f;
    EXPECT_GT(Iou(results[0].box, SquareBox(f)), 0.5) << "frame " << f;
    const cv::Mat mask = tracker->Mask(id);
    ASSERT_FALSE(mask.empty());
    EXPECT_EQ(mask.size(), kSize);
    EXPECT_GT(Iou(cv::boundingRect(mask), SquareBox(f)), 0.5) << "frame " << f;
    EXPECT_GE(tracker->milliseconds(), 0.0);
  }
  tracker->Remove(id);
  EXPECT_TRUE(tracker->ids().empty());
  EXPECT_TRUE(tracker->Mask(id).empty());
}

TEST_P(EveryKind, NothingToStartOnGivesMinusOne) {
  const std::unique_ptr<TargetTracker> tracker = Make(GetParam());
  const cv::Mat frame = Scene(0);
  EXPECT_EQ(tracker->StartFromMask(frame, cv::Mat::zeros(kSize, CV_8UC1)), -1);
  EXPECT_EQ(tracker->StartFromBox(frame, cv::Rect(500, 500, 10, 10)), -1);
  cv::Mat labels(kSize, CV_32SC1, cv::Scalar(0));
  EXPECT_EQ(tracker->StartFromRegion(frame, labels, 3), -1);
  EXPECT_TRUE(tracker->ids().empty());
}

INSTANTIATE_TEST_SUITE_P(Kinds, EveryKind,
                         ::testing::Values(TrackerKind::kBip, TrackerKind::kKcf,
                                           TrackerKind::kCsrt),
                         [](const ::testing::TestParamInfo<TrackerKind>& info) {
                           return std::string(TrackerKindName(info.param));
                         });

// The OpenCV kinds' mask is the start shape scaled to the box: a disc started from its region
// stays a disc (its area, not the box's), moved with the box.
TEST(OpenCvTargetTracker, MaskIsTheStartShapeMovedWithTheBox) {
  for (const TrackerKind kind : {TrackerKind::kKcf, TrackerKind::kCsrt}) {
    SCOPED_TRACE(TrackerKindName(kind));
    const std::unique_ptr<TargetTracker> tracker = Make(kind);
    const cv::Mat frame = Scene(0);
    cv::Mat labels(kSize, CV_32SC1, cv::Scalar(0));
    const cv::Rect box = SquareBox(0);
    cv::circle(labels, (box.tl() + box.br()) / 2, kSide / 2, cv::Scalar(5), cv::FILLED);
    const int disc = cv::countNonZero(labels == 5);
    const int id = tracker->StartFromRegion(frame, labels, 5);
    ASSERT_EQ(id, 1);
    EXPECT_EQ(cv::countNonZero(tracker->Mask(id) != (labels == 5)), 0);
    std::vector<TrackResult> results;
    tracker->Track(Scene(1), &results);
    ASSERT_EQ(results.size(), 1u);
    ASSERT_EQ(results[0].state, TrackState::kFound);
    const cv::Mat mask = tracker->Mask(id);
    EXPECT_EQ(results[0].area, cv::countNonZero(mask));
    // About the disc's area (the box may change scale a little), well under the box's.
    EXPECT_NEAR(results[0].area, disc, 0.2 * disc);
    EXPECT_LT(results[0].area, 0.85 * results[0].box.area());
    EXPECT_GT(Iou(cv::boundingRect(mask), results[0].box), 0.9);
  }
}

// A target that vanishes: KCF reports failure, so it is occluded at its last box, then lost
// after lost_frames failures in a row, reported once and removed.
TEST(OpenCvTargetTracker, FailuresAreOccludedThenLostAfterLostFrames) {
  constexpr int kLostFrames = 4;
  const std::unique_ptr<TargetTracker> tracker = Make(TrackerKind::kKcf, kLostFrames);
  const int id = tracker->StartFromBox(Scene(0), SquareBox(0));
  ASSERT_EQ(id, 1);
  std::vector<TrackResult> results;
  cv::Rect last;
  for (int f = 1; f <= 5; ++f) {
    results.clear();
    tracker->Track(Scene(f), &results);
    ASSERT_EQ(results[0].state, TrackState::kFound) << "frame " << f;
    last = results[0].box;
  }
  std::vector<TrackState> states;
  for (int f = 6; f < 6 + kLostFrames; ++f) {
    results.clear();
    tracker->Track(Scene(f, /*visible=*/false), &results);
    ASSERT_EQ(results.size(), 1u) << "frame " << f;
    states.push_back(results[0].state);
    EXPECT_EQ(results[0].box, last) << "frame " << f;
    EXPECT_TRUE(tracker->Mask(id).empty() || results[0].state == TrackState::kFound);
  }
  const std::vector<TrackState> expected = {TrackState::kOccluded, TrackState::kOccluded,
                                            TrackState::kOccluded, TrackState::kLost};
  EXPECT_EQ(states, expected);
  EXPECT_TRUE(tracker->ids().empty());
  results.clear();
  tracker->Track(Scene(10), &results);
  EXPECT_TRUE(results.empty());
}

// The bip kind is MultiTracker: the same boxes, states and masks, frame by frame.
TEST(BipTargetTracker, GivesWhatMultiTrackerGives) {
  TargetTrackerOptions options;
  const std::unique_ptr<TargetTracker> wrapped = TargetTracker::Create(options);
  MultiTracker direct(options.bip);
  ASSERT_EQ(wrapped->StartFromBox(Scene(0), SquareBox(0)),
            direct.StartFromBox(Scene(0), SquareBox(0)));
  ASSERT_FALSE(wrapped->ids().empty());
  for (int f = 1; f < 12; ++f) {
    std::vector<TrackResult> a, b;
    wrapped->Track(Scene(f), &a);
    direct.Track(Scene(f), &b);
    ASSERT_EQ(a.size(), b.size());
    for (size_t i = 0; i < a.size(); ++i) {
      EXPECT_EQ(a[i].box, b[i].box) << "frame " << f;
      EXPECT_EQ(a[i].state, b[i].state) << "frame " << f;
      EXPECT_EQ(cv::countNonZero(wrapped->Mask(a[i].id) != direct.Mask(b[i].id)), 0);
    }
  }
}

}  // namespace
}  // namespace attend
