// The MOTChallenge measures (eval/mot_metrics.h): EvaluateMot on runs built here whose CLEAR
// MOT, identity and attention scores are worked out by hand in the comments.
#include "eval/mot_metrics.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <numeric>
#include <random>
#include <vector>

namespace attend {
namespace {

constexpr double kTolerance = 1e-12;

// ------------------------------------------------------------------------------------------
// EvaluateMot

GtObject Object(int frame, int id, const cv::Rect2d& box, double visible_fraction = 1.0) {
  GtObject object;
  object.frame = frame;
  object.id = id;
  object.box = box;
  object.visible_fraction = visible_fraction;
  return object;
}

TargetRecord MotTarget(int id, const cv::Rect& box, TargetState state = TargetState::kTracked) {
  TargetRecord target;
  target.id = id;
  target.bbox = box;
  target.state = state;
  return target;
}

// Frames 0..count-1 without targets.
std::vector<FrameRecord> Frames(int count) {
  std::vector<FrameRecord> frames(count);
  for (int f = 0; f < count; ++f) frames[f].frame = f;
  return frames;
}

MotOptions AtIou(double match_iou) {
  MotOptions options;
  options.match_iou = match_iou;
  return options;
}

const cv::Rect kPersonA(10, 10, 100, 200);
const cv::Rect kPersonB(300, 10, 100, 200);

TEST(MotOptions, DefaultsAreValid) {
  EXPECT_EQ(MotOptions{}.Check(), "");
  EXPECT_DOUBLE_EQ(MotOptions{}.match_iou, 0.5);
  EXPECT_DOUBLE_EQ(MotOptions{}.min_visible, EvaluationOptions{}.min_visible);
  EXPECT_DOUBLE_EQ(MotOptions{}.min_area, EvaluationOptions{}.min_area);
}

TEST(MotOptions, CheckNamesTheField) {
  MotOptions options;
  options.match_iou = 0.0;
  EXPECT_NE(options.Check().find("match_iou"), std::string::npos) << options.Check();
  options = {};
  options.mostly_lost = 0.9;
  EXPECT_EQ(options.Check(), "mostly_lost must be <= mostly_tracked");
}

TEST(EvaluateMot, APerfectTrackerScoresOne) {
  std::vector<FrameRecord> frames = Frames(5);
  std::vector<GtObject> truth;
  for (FrameRecord& record : frames) {
    truth.push_back(Object(record.frame, 1, kPersonA));
    truth.push_back(Object(record.frame, 2, kPersonB));
    record.targets = {MotTarget(7, kPersonA), MotTarget(8, kPersonB)};
  }
  frames[0].targets[0].state = frames[0].targets[1].state = TargetState::kNew;
  const MotScores scores = EvaluateMot(frames, truth);
  EXPECT_EQ(scores.frames, 5);
  EXPECT_EQ(scores.objects, 2);
  EXPECT_EQ(scores.gt, 10);
  EXPECT_EQ(scores.matches, 10);
  EXPECT_EQ(scores.false_positives, 0);
  EXPECT_EQ(scores.false_negatives, 0);
  EXPECT_EQ(scores.id_switches, 0);
  EXPECT_DOUBLE_EQ(scores.mota, 1.0);
  EXPECT_DOUBLE_EQ(scores.motp, 1.0);
  EXPECT_EQ(scores.mostly_tracked, 2);
  EXPECT_EQ(scores.partly_tracked, 0);
  EXPECT_EQ(scores.mostly_lost, 0);
  EXPECT_EQ(scores.fragmentations, 0);
  EXPECT_EQ(scores.idtp, 10);
  EXPECT_EQ(scores.idfp, 0);
  EXPECT_EQ(scores.idfn, 0);
  EXPECT_DOUBLE_EQ(scores.idf1, 1.0);
  EXPECT_DOUBLE_EQ(scores.idp, 1.0);
  EXPECT_DOUBLE_EQ(scores.idr, 1.0);
  EXPECT_EQ(scores.objects_attended_whole, 2);
  EXPECT_DOUBLE_EQ(scores.attended_whole_fraction, 1.0);
  EXPECT_DOUBLE_EQ(scores.ids_per_attended_object, 1.0);
  EXPECT_DOUBLE_EQ(scores.purity, 1.0);
  EXPECT_EQ(scores.targets_started, 2);
}

TEST(EvaluateMot, OneIdSwitchInTheMiddle) {
  // Person A for 10 frames: target 1 in frames 0-3, target 2 in 4-9. Person B: target 3
  // throughout. GT 20, no FN or FP, one switch: MOTA = 1 - 1/20 = 0.95.
  // Identity: A pairs with target 2 (6 frames, against 4 with target 1), B with 3 (10):
  // IDTP 16, IDFP 4 (target 1), IDFN 4 (A's frames 0-3); IDF1 = 32 / (32 + 4 + 4) = 0.8.
  std::vector<FrameRecord> frames = Frames(10);
  std::vector<GtObject> truth;
  for (FrameRecord& record : frames) {
    truth.push_back(Object(record.frame, 1, kPersonA));
    truth.push_back(Object(record.frame, 2, kPersonB));
    record.targets = {MotTarget(record.frame < 4 ? 1 : 2, kPersonA), MotTarget(3, kPersonB)};
  }
  const MotScores scores = EvaluateMot(frames, truth);
  EXPECT_EQ(scores.gt, 20);
  EXPECT_EQ(scores.false_negatives, 0);
  EXPECT_EQ(scores.false_positives, 0);
  EXPECT_EQ(scores.id_switches, 1);
  EXPECT_NEAR(scores.mota, 0.95, kTolerance);
  EXPECT_EQ(scores.idtp, 16);
  EXPECT_EQ(scores.idfp, 4);
  EXPECT_EQ(scores.idfn, 4);
  EXPECT_NEAR(scores.idf1, 0.8, kTolerance);
  EXPECT_NEAR(scores.idp, 0.8, kTolerance);
  EXPECT_NEAR(scores.idr, 0.8, kTolerance);
  EXPECT_EQ(scores.fragmentations, 0);                           // matched in every frame
  EXPECT_NEAR(scores.ids_per_attended_object, 1.5, kTolerance);  // A 2 ids, B 1
  EXPECT_DOUBLE_EQ(scores.purity, 1.0);                          // each target stays on one person
  EXPECT_EQ(scores.targets_started, 3);
}

TEST(EvaluateMot, APartOfAPersonMatchesAtPointThreeNotAtPointFive) {
  // The upper 80 of the person's 200 rows: IoU 0.4.
  std::vector<FrameRecord> frames = Frames(1);
  frames[0].targets = {MotTarget(1, cv::Rect(10, 10, 100, 80), TargetState::kNew)};
  const std::vector<GtObject> truth = {Object(0, 1, kPersonA)};

  const MotScores strict = EvaluateMot(frames, truth, AtIou(0.5));
  EXPECT_EQ(strict.gt, 1);
  EXPECT_EQ(strict.matches, 0);
  EXPECT_EQ(strict.false_negatives, 1);
  EXPECT_EQ(strict.false_positives, 1);
  EXPECT_DOUBLE_EQ(strict.mota, -1.0);  // 1 - (1 + 1) / 1
  EXPECT_EQ(strict.objects_attended_whole, 0);
  EXPECT_EQ(strict.mostly_lost, 1);
  EXPECT_DOUBLE_EQ(strict.idf1, 0.0);

  const MotScores loose = EvaluateMot(frames, truth, AtIou(0.3));
  EXPECT_EQ(loose.matches, 1);
  EXPECT_EQ(loose.false_negatives, 0);
  EXPECT_EQ(loose.false_positives, 0);
  EXPECT_DOUBLE_EQ(loose.mota, 1.0);
  EXPECT_NEAR(loose.motp, 0.4, kTolerance);
  EXPECT_EQ(loose.objects_attended_whole, 1);
  EXPECT_DOUBLE_EQ(loose.idf1, 1.0);
}

TEST(EvaluateMot, ExactlyTheThresholdMatches) {
  // The upper half of the person: IoU exactly 0.5, which MOTChallenge counts as a match.
  std::vector<FrameRecord> frames = Frames(1);
  frames[0].targets = {MotTarget(1, cv::Rect(10, 10, 100, 100))};
  const MotScores scores = EvaluateMot(frames, {Object(0, 1, kPersonA)});
  EXPECT_EQ(scores.matches, 1);
  EXPECT_DOUBLE_EQ(scores.motp, 0.5);
}

TEST(EvaluateMot, TwoTargetsOnOnePersonOneAfterTheOther) {
  // Person A for 6 frames: target 1 in frames 0-1, occluded (not seen) in 2-3, target 2 in
  // 4-5. Matched in 4 of 6 frames (partly tracked), in two streaks (one fragmentation), one
  // switch; GT 6, FN 2, MOTA = 1 - 3/6.
  std::vector<FrameRecord> frames = Frames(6);
  std::vector<GtObject> truth;
  for (FrameRecord& record : frames) {
    truth.push_back(Object(record.frame, 1, kPersonA));
    if (record.frame < 2) record.targets = {MotTarget(1, kPersonA)};
    if (record.frame == 2 || record.frame == 3) {
      record.targets = {MotTarget(1, kPersonA, TargetState::kOccluded)};
    }
    if (record.frame >= 4) record.targets = {MotTarget(2, kPersonA)};
  }
  const MotScores scores = EvaluateMot(frames, truth);
  EXPECT_EQ(scores.objects_attended_whole, 1);
  EXPECT_DOUBLE_EQ(scores.ids_per_attended_object, 2.0);
  EXPECT_EQ(scores.id_switches, 1);
  EXPECT_EQ(scores.false_negatives, 2);
  EXPECT_EQ(scores.false_positives, 0);  // the occluded target is not seen
  EXPECT_DOUBLE_EQ(scores.mota, 0.5);
  EXPECT_EQ(scores.fragmentations, 1);
  EXPECT_EQ(scores.partly_tracked, 1);
  EXPECT_EQ(scores.mostly_tracked, 0);
  EXPECT_DOUBLE_EQ(scores.purity, 1.0);
  EXPECT_EQ(scores.targets_started, 2);
}

TEST(EvaluateMot, ATargetThatMovesFromOnePersonToAnother) {
  // Target 1 on person A in frames 0-2, then on person B in 3-4; both people in all 5 frames.
  // Purity 3/5. No switch (B's first match, A's last one), FN 5 of GT 10: MOTA 0.5.
  // Identity: target 1 pairs with A (3 frames against 2): IDTP 3, IDFP 2, IDFN 7,
  // IDF1 = 6 / (6 + 2 + 7) = 0.4.
  std::vector<FrameRecord> frames = Frames(5);
  std::vector<GtObject> truth;
  for (FrameRecord& record : frames) {
    truth.push_back(Object(record.frame, 1, kPersonA));
    truth.push_back(Object(record.frame, 2, kPersonB));
    record.targets = {MotTarget(1, record.frame < 3 ? kPersonA : kPersonB)};
  }
  const MotScores scores = EvaluateMot(frames, truth);
  EXPECT_NEAR(scores.purity, 0.6, kTolerance);
  EXPECT_EQ(scores.id_switches, 0);
  EXPECT_EQ(scores.false_negatives, 5);
  EXPECT_DOUBLE_EQ(scores.mota, 0.5);
  EXPECT_EQ(scores.idtp, 3);
  EXPECT_EQ(scores.idfp, 2);
  EXPECT_EQ(scores.idfn, 7);
  EXPECT_NEAR(scores.idf1, 0.4, kTolerance);
  EXPECT_EQ(scores.objects_attended_whole, 2);
  EXPECT_DOUBLE_EQ(scores.ids_per_attended_object, 1.0);
}

TEST(EvaluateMot, FalsePositivesAndNegativesOnAConstructedRun) {
  // Frames 0-2: person A under target 1 throughout; person B (frames 0-1) under target 3 in
  // frame 0 only, under the occluded target 9 in frame 1 (not seen: B is missed); target 2 on
  // the wall in frames 0-2. Frame 3 has no ground truth, and target 1 is a false positive there.
  // GT 5 (A 3, B 2), FN 1, FP 3 + 1, MOTA = 1 - 5/5 = 0.
  // Identity: A with 1 (3 frames), B with 3 (1): IDTP 4; target boxes 4 + 3 + 1 = 8, IDFP 4,
  // IDFN 1; IDF1 = 8 / 13.
  const cv::Rect wall(500, 300, 40, 40);
  std::vector<FrameRecord> frames = Frames(4);
  std::vector<GtObject> truth;
  for (int f = 0; f < 3; ++f) truth.push_back(Object(f, 1, kPersonA));
  for (int f = 0; f < 2; ++f) truth.push_back(Object(f, 2, kPersonB));
  frames[0].targets = {MotTarget(1, kPersonA, TargetState::kNew), MotTarget(2, wall, TargetState::kNew),
                       MotTarget(3, kPersonB, TargetState::kNew)};
  frames[1].targets = {MotTarget(1, kPersonA), MotTarget(2, wall),
                       MotTarget(3, kPersonB, TargetState::kLost),
                       MotTarget(9, kPersonB, TargetState::kOccluded)};
  frames[2].targets = {MotTarget(1, kPersonA), MotTarget(2, wall)};
  frames[3].targets = {MotTarget(1, kPersonA)};
  const MotScores scores = EvaluateMot(frames, truth);
  EXPECT_EQ(scores.frames, 4);
  EXPECT_EQ(scores.gt, 5);
  EXPECT_EQ(scores.matches, 4);
  EXPECT_EQ(scores.false_negatives, 1);
  EXPECT_EQ(scores.false_positives, 4);
  EXPECT_EQ(scores.id_switches, 0);
  EXPECT_EQ(scores.ignored, 0);
  EXPECT_NEAR(scores.mota, 0.0, kTolerance);
  EXPECT_DOUBLE_EQ(scores.motp, 1.0);
  EXPECT_EQ(scores.idtp, 4);
  EXPECT_EQ(scores.idfp, 4);
  EXPECT_EQ(scores.idfn, 1);
  EXPECT_NEAR(scores.idf1, 8.0 / 13.0, kTolerance);
  EXPECT_EQ(scores.mostly_tracked, 1);   // A 3/3
  EXPECT_EQ(scores.partly_tracked, 1);   // B 1/2
  EXPECT_EQ(scores.targets_started, 4);  // 1, 2, 3 and 9, in any state
}

TEST(EvaluateMot, TheAssignmentMatchesMorePairsThanTheGreedyChoice) {
  // Target 1 is person A's box exactly (IoU 1) and overlaps B (at x + 30) with IoU 7/13;
  // target 2, A's left 80 columns, overlaps A with IoU 0.8 and B with 5/13 < 0.5. Greedy by
  // IoU pairs 1 with A and leaves B and 2 alone; the assignment pairs 1 with B, 2 with A.
  std::vector<FrameRecord> frames = Frames(1);
  frames[0].targets = {MotTarget(1, cv::Rect(0, 0, 100, 100)), MotTarget(2, cv::Rect(0, 0, 80, 100))};
  const std::vector<GtObject> truth = {Object(0, 1, {0, 0, 100, 100}),
                                       Object(0, 2, {30, 0, 100, 100})};
  const MotScores scores = EvaluateMot(frames, truth);
  EXPECT_EQ(scores.matches, 2);
  EXPECT_EQ(scores.false_negatives, 0);
  EXPECT_EQ(scores.false_positives, 0);
  EXPECT_NEAR(scores.motp, (0.8 + 7.0 / 13.0) / 2.0, kTolerance);
}

TEST(EvaluateMot, LastFramesPairIsKeptWhileItReachesTheThreshold) {
  // Frame 0: target 1 covers the upper 60 % of person A (IoU 0.6). Frame 1: target 1 again,
  // and target 2 exactly on A. CLEAR MOT keeps 1 on A, so 2 is a false positive and there is
  // no switch; frame 2: target 1 drops to IoU 0.4, and A goes to 2 (one switch).
  const cv::Rect upper(10, 10, 100, 120), upper_part(10, 10, 100, 80);
  std::vector<FrameRecord> frames = Frames(3);
  frames[0].targets = {MotTarget(1, upper)};
  frames[1].targets = {MotTarget(1, upper), MotTarget(2, kPersonA)};
  frames[2].targets = {MotTarget(1, upper_part), MotTarget(2, kPersonA)};
  std::vector<GtObject> truth;
  for (int f = 0; f < 3; ++f) truth.push_back(Object(f, 1, kPersonA));
  const MotScores scores = EvaluateMot(frames, truth);
  EXPECT_EQ(scores.matches, 3);
  EXPECT_EQ(scores.id_switches, 1);
  EXPECT_EQ(scores.false_positives, 2);  // 2 in frame 1, 1 in frame 2
  EXPECT_NEAR(scores.motp, (0.6 + 0.6 + 1.0) / 3.0, kTolerance);
}

TEST(EvaluateMot, ATargetOnAnObjectThatDoesNotCountIsIgnored) {
  // Person A is 10 % visible and person B smaller than 64 px: neither counts, and targets on
  // them are neither false positives nor part of the identity measures. Target 3 on the wall is
  // a false positive.
  std::vector<FrameRecord> frames = Frames(1);
  frames[0].targets = {MotTarget(1, kPersonA), MotTarget(2, cv::Rect(300, 10, 7, 7)),
                       MotTarget(3, cv::Rect(500, 300, 40, 40))};
  const std::vector<GtObject> truth = {Object(0, 1, kPersonA, 0.1), Object(0, 2, {300, 10, 7, 7})};
  const MotScores scores = EvaluateMot(frames, truth);
  EXPECT_EQ(scores.objects, 0);
  EXPECT_EQ(scores.gt, 0);
  EXPECT_EQ(scores.ignored, 2);
  EXPECT_EQ(scores.false_positives, 1);
  EXPECT_EQ(scores.idfp, 1);
  EXPECT_DOUBLE_EQ(scores.mota, 0.0);  // no ground truth: 0, not a division by zero
  EXPECT_DOUBLE_EQ(scores.attended_whole_fraction, 0.0);
  EXPECT_EQ(scores.targets_started, 3);
}

TEST(EvaluateMot, NothingToScore) {
  const MotScores scores = EvaluateMot({}, {});
  EXPECT_EQ(scores.frames, 0);
  EXPECT_EQ(scores.gt, 0);
  EXPECT_DOUBLE_EQ(scores.mota, 0.0);
  EXPECT_DOUBLE_EQ(scores.idf1, 0.0);
  EXPECT_DOUBLE_EQ(scores.purity, 0.0);
}

}  // namespace
}  // namespace attend
