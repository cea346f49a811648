// Recognition (semiattentive/recognition.h) and the followed targets
// (semiattentive/followed_targets.h): targets matched to detections one to one, re-anchoring,
// the unrecognised count, labels, and the ids of new and resumed targets.
#include "semiattentive/recognition.h"

#include <gtest/gtest.h>

namespace attend {
namespace {

TrackResult Found(int id, const cv::Rect& box) {
  TrackResult result;
  result.id = id;
  result.box = box;
  return result;
}

TEST(Recogniser, TargetsAndDetectionsMatchOneToOneAndSkinTargetsNever) {
  FollowedTargets targets;
  FollowedTarget a, b, skin;
  a.tracker_id = 10;
  b.tracker_id = 11;
  skin.tracker_id = 12;
  skin.skin = true;
  targets.Add(a);
  targets.Add(b);
  targets.Add(skin);
  // The drifted b overlaps a's detection more than its own; one to one, each keeps its own.
  const std::vector<TrackResult> results = {Found(10, cv::Rect(0, 0, 10, 10)),
                                            Found(11, cv::Rect(4, 0, 10, 10)),
                                            Found(12, cv::Rect(0, 0, 10, 10))};
  const std::vector<Detection> detections = {{cv::Rect(9, 0, 10, 10), "person", 0.5f},
                                             {cv::Rect(0, 0, 10, 10), "person", 0.5f}};
  Recogniser recogniser(SelectOptions(), DropOptions(), 0.5f);
  EXPECT_EQ(recogniser.MatchDetections(results, targets, detections, cv::Rect(0, 0, 50, 50)),
            (std::vector<int>{1, 0, -1}));
  EXPECT_EQ(recogniser.MatchDetections(results, targets, {}, cv::Rect(0, 0, 50, 50)),
            (std::vector<int>{-1, -1, -1}));
}

// Background (region 0) with region 1 at (10, 10, 10, 10) and region 2 right of it.
Segmentation Drawn() {
  Segmentation segmentation;
  segmentation.labels = cv::Mat::zeros(40, 60, CV_32SC1);
  segmentation.labels(cv::Rect(10, 10, 10, 10)).setTo(1);
  segmentation.labels(cv::Rect(20, 10, 10, 10)).setTo(2);
  segmentation.regions.resize(3);
  segmentation.regions[0].area = 40 * 60 - 200;
  segmentation.regions[1].area = segmentation.regions[2].area = 100;
  return segmentation;
}

TEST(Recogniser, ATargetOnPartOfItsDetectionReanchorsOnTheDetectionsSeed) {
  SelectOptions select;
  select.reanchor_min_iou = 0.2f;
  select.min_area = 50;
  Recogniser recogniser(select, DropOptions(), 0.5f);
  SeedMaker seeds(select);
  const Segmentation segmentation = Drawn();
  const cv::Mat bgr(40, 60, CV_8UC3, cv::Scalar(90, 120, 150));
  const std::vector<Detection> detections = {{cv::Rect(10, 10, 20, 10), "person", 0.9f}};
  FollowedTarget target;
  target.unrecognised = 3;
  Seed seed;
  // IoU 0.5, in [0.2, 0.75): re-anchored on regions 1 and 2.
  Recognition recognition = recogniser.Recognise(
      bgr, segmentation, detections, cv::Rect(10, 10, 10, 10), 0, &seeds, &target, &seed);
  EXPECT_EQ(recognition.detection, 0);
  EXPECT_TRUE(recognition.reanchor);
  EXPECT_FALSE(recognition.unrecognised);
  EXPECT_EQ(target.unrecognised, 0);
  EXPECT_EQ(cv::countNonZero(seed.mask), 200);
  // On the whole detection (IoU 1): recognised, nothing to re-anchor.
  recognition = recogniser.Recognise(bgr, segmentation, detections, cv::Rect(10, 10, 20, 10), 0,
                                     &seeds, &target, &seed);
  EXPECT_EQ(recognition.detection, 0);
  EXPECT_FALSE(recognition.reanchor);
}

TEST(Recogniser, ALabelledTargetNoDetectionIsOnIsReleasedAfterTheFramesSet) {
  DropOptions drop;
  drop.unrecognised_frames = 2;
  Recogniser recogniser(SelectOptions(), drop, 0.5f);
  SeedMaker seeds{SelectOptions()};
  const Segmentation segmentation = Drawn();
  const cv::Mat bgr(40, 60, CV_8UC3, cv::Scalar(0));
  const std::vector<Detection> detections = {{cv::Rect(40, 20, 10, 10), "person", 0.9f}};
  FollowedTarget target;
  Seed seed;
  const cv::Rect box(10, 10, 10, 10);
  // Unlabelled: never released as unrecognised.
  for (int i = 0; i < 3; ++i) {
    EXPECT_FALSE(
        recogniser.Recognise(bgr, segmentation, detections, box, -1, &seeds, &target, &seed)
            .unrecognised);
  }
  target.label = "person";
  target.unrecognised = 0;
  EXPECT_FALSE(recogniser.Recognise(bgr, segmentation, detections, box, -1, &seeds, &target, &seed)
                   .unrecognised);
  EXPECT_TRUE(recogniser.Recognise(bgr, segmentation, detections, box, -1, &seeds, &target, &seed)
                  .unrecognised);
}

TEST(Recogniser, ATargetTakesTheLabelOfTheDetectionOverlappingEnoughOfTheLargerBox) {
  Recogniser recogniser(SelectOptions(), DropOptions(), 0.5f);
  const cv::Rect box(0, 0, 10, 10);
  EXPECT_EQ(recogniser.LabelOf(box, {{cv::Rect(0, 0, 10, 20), "person", 0.5f}}), "person");
  EXPECT_EQ(recogniser.LabelOf(box, {{cv::Rect(0, 0, 10, 30), "person", 0.5f}}), "");
  EXPECT_EQ(recogniser.LabelOf(box, {{cv::Rect(0, 0, 10, 20), "person", 0.5f},
                                     {cv::Rect(0, 0, 10, 12), "face", 0.5f}}),
            "face");
}

TEST(FollowedTargets, NewTargetsGetTheNextIdAndResumedOnesKeepTheirs) {
  FollowedTargets targets;
  FollowedTarget target;
  target.tracker_id = 4;
  EXPECT_EQ(targets.Add(target), 1);
  target.tracker_id = 5;
  EXPECT_EQ(targets.Add(target), 2);
  ObjectFile file;
  file.id = 1;
  file.label = "person";
  FollowedTarget resumed;
  resumed.tracker_id = 6;
  resumed.Resume(file);
  EXPECT_EQ(targets.Add(resumed), 1);
  EXPECT_EQ(targets.attended(), 2);
  EXPECT_EQ(targets.size(), 3);
  ASSERT_NE(targets.OfTracker(6), nullptr);
  EXPECT_EQ(targets.OfTracker(6)->label, "person");
  targets.RemoveTrackers({4, 6});
  EXPECT_EQ(targets.size(), 1);
  EXPECT_EQ(targets.OfTracker(4), nullptr);
  EXPECT_EQ(targets.WithId(2)->tracker_id, 5);
}

TEST(FollowedTarget, ItsVelocityFollowsItsDisplacementPerFrameSinceItWasKept) {
  FollowedTarget target;
  target.Kept(cv::Rect(0, 0, 10, 10), ObjectAppearance());
  target.since_kept = 2;
  target.Kept(cv::Rect(10, 0, 10, 10), ObjectAppearance());  // 5 px a frame
  EXPECT_FLOAT_EQ(target.velocity.x, 0.3f * 5.f);
  EXPECT_EQ(target.since_kept, 0);
  EXPECT_EQ(target.File().box, cv::Rect(10, 0, 10, 10));
}

}  // namespace
}  // namespace attend
