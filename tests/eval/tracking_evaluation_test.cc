// tracks.csv and OTB ground truth as files, and the OTB one-pass scores on boxes whose overlaps
// are known by hand (io/tracking_files.h, eval/tracking_scores.h, docs/TRACKING.md).
#include "eval/tracking_scores.h"
#include "io/tracking_files.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "tests/support/error_message.h"
#include "tests/support/temp_dir.h"
#include "util/error.h"

namespace attend {
namespace {

using testing::InputErrorOf;
using testing::TempDir;

constexpr double kTolerance = 1e-12;

// ------------------------------------------------------------------------------------------
// ScoreTracking

TEST(ScoreTracking, PerfectTrackScoresTwentyOfTwentyOneThresholds) {
  const std::vector<cv::Rect2d> truth = {{10, 20, 30, 40}, {12, 21, 30, 40}, {15, 22, 28, 41}};
  const TrackingScores scores = ScoreTracking(truth, truth);
  EXPECT_EQ(scores.frames, 3);
  ASSERT_EQ(scores.success.size(), 21u);
  // IoU 1 exceeds every threshold but the last one, 1.
  for (int k = 0; k < 20; ++k) EXPECT_DOUBLE_EQ(scores.success[k], 1.0) << "threshold " << k;
  EXPECT_DOUBLE_EQ(scores.success[20], 0.0);
  EXPECT_NEAR(scores.success_auc, 20.0 / 21.0, kTolerance);
  EXPECT_DOUBLE_EQ(scores.precision_20, 1.0);
  EXPECT_DOUBLE_EQ(scores.mean_iou, 1.0);
}

TEST(ScoreTracking, BoxShiftedByHalfItsWidthHasIouOneThird) {
  // 10x10 boxes 5 px apart: intersection 50, union 150, IoU 1/3; centres 5 px apart.
  const std::vector<cv::Rect2d> truth = {{0, 0, 10, 10}, {40, 40, 10, 10}};
  const std::vector<cv::Rect2d> predicted = {{5, 0, 10, 10}, {40, 45, 10, 10}};
  const TrackingScores scores = ScoreTracking(predicted, truth);
  EXPECT_EQ(scores.frames, 2);
  // 1/3 > t for t = 0, 0.05, ..., 0.30 (7 thresholds), not for 0.35 and above.
  for (int k = 0; k < 21; ++k) {
    EXPECT_DOUBLE_EQ(scores.success[k], k <= 6 ? 1.0 : 0.0) << "threshold " << k;
  }
  EXPECT_NEAR(scores.success_auc, 7.0 / 21.0, kTolerance);
  EXPECT_DOUBLE_EQ(scores.precision_20, 1.0);
  EXPECT_NEAR(scores.mean_iou, 1.0 / 3.0, kTolerance);
}

TEST(ScoreTracking, SuccessNeedsIouStrictlyAboveTheThreshold) {
  // The lower half of the true box: IoU exactly 0.5, which is not > 0.5.
  const std::vector<cv::Rect2d> truth = {{0, 0, 10, 10}};
  const std::vector<cv::Rect2d> predicted = {{0, 5, 10, 5}};
  const TrackingScores scores = ScoreTracking(predicted, truth);
  for (int k = 0; k < 21; ++k) {
    EXPECT_DOUBLE_EQ(scores.success[k], k <= 9 ? 1.0 : 0.0) << "threshold " << k;
  }
  EXPECT_NEAR(scores.success_auc, 10.0 / 21.0, kTolerance);
  EXPECT_DOUBLE_EQ(scores.mean_iou, 0.5);
}

TEST(ScoreTracking, PrecisionCountsCentreErrorsUpToTwentyPixelsInclusive) {
  const cv::Rect2d box(100, 100, 20, 20);
  // Centre errors 20 (12 and 16 px apart), 20.0000001 and 25 (15 and 20) px; only the first
  // overlaps the truth.
  const std::vector<cv::Rect2d> truth = {box, box, box};
  const std::vector<cv::Rect2d> predicted = {
      {112, 116, 20, 20}, {130.0000001, 100, 20, 20}, {115, 120, 20, 20}};
  const TrackingScores scores = ScoreTracking(predicted, truth);
  // Only the first is within 20 px (the second is just beyond, the third is 25 px away).
  EXPECT_NEAR(scores.precision_20, 1.0 / 3.0, kTolerance);
  // Overlaps: 8 x 4 = 32 of 400 + 400 - 32, then none.
  EXPECT_NEAR(scores.mean_iou, (32.0 / 768.0) / 3.0, kTolerance);
}

TEST(ScoreTracking, MissingAndEmptyPredictionsScoreZero) {
  const std::vector<cv::Rect2d> truth(4, cv::Rect2d(0, 0, 10, 10));
  // Frame 1 not found (empty box), frames 2 and 3 beyond the predictions.
  const std::vector<cv::Rect2d> predicted = {{0, 0, 10, 10}, cv::Rect2d()};
  const TrackingScores scores = ScoreTracking(predicted, truth);
  EXPECT_EQ(scores.frames, 4);
  for (int k = 0; k < 20; ++k) EXPECT_DOUBLE_EQ(scores.success[k], 0.25);
  EXPECT_NEAR(scores.success_auc, (20 * 0.25) / 21.0, kTolerance);
  EXPECT_DOUBLE_EQ(scores.precision_20, 0.25);
  EXPECT_DOUBLE_EQ(scores.mean_iou, 0.25);
}

TEST(ScoreTracking, FramesWithoutGroundTruthAreSkipped) {
  // The object is hidden in frames 1 and 3: whatever is predicted there does not count.
  const std::vector<cv::Rect2d> truth = {
      {0, 0, 10, 10}, cv::Rect2d(), {20, 0, 10, 10}, cv::Rect2d(5, 5, 0, 7)};
  const std::vector<cv::Rect2d> predicted = {
      {0, 0, 10, 10}, {200, 200, 5, 5}, {25, 0, 10, 10}, cv::Rect2d()};
  const TrackingScores scores = ScoreTracking(predicted, truth);
  EXPECT_EQ(scores.frames, 2);
  // IoU 1 and 1/3.
  EXPECT_NEAR(scores.mean_iou, (1.0 + 1.0 / 3.0) / 2.0, kTolerance);
  EXPECT_NEAR(scores.success_auc, (7 * 1.0 + 13 * 0.5) / 21.0, kTolerance);
  EXPECT_DOUBLE_EQ(scores.precision_20, 1.0);
}

TEST(ScoreTracking, PredictionsBeyondTheTruthAreIgnored) {
  const std::vector<cv::Rect2d> truth = {{0, 0, 10, 10}};
  const std::vector<cv::Rect2d> predicted = {{0, 0, 10, 10}, {50, 50, 10, 10}};
  EXPECT_EQ(ScoreTracking(predicted, truth).frames, 1);
  EXPECT_NEAR(ScoreTracking(predicted, truth).success_auc, 20.0 / 21.0, kTolerance);
}

TEST(ScoreTracking, NoGroundTruthGivesZeros) {
  const TrackingScores scores = ScoreTracking({{0, 0, 5, 5}}, {cv::Rect2d()});
  EXPECT_EQ(scores.frames, 0);
  EXPECT_EQ(scores.success.size(), 21u);
  EXPECT_EQ(scores.success_auc, 0.0);
  EXPECT_EQ(scores.precision_20, 0.0);
  EXPECT_EQ(scores.mean_iou, 0.0);
}

TEST(ScoreTracking, TouchingBoxesDoNotOverlap) {
  const TrackingScores scores = ScoreTracking({{10, 0, 10, 10}}, {{0, 0, 10, 10}});
  EXPECT_EQ(scores.success[0], 0.0);
  EXPECT_EQ(scores.precision_20, 1.0);  // centres 10 px apart
}

TEST(ScoreTracking, PrecisionCurveCountsCentreErrorsUpToEachPixelThreshold) {
  const cv::Rect2d box(100, 100, 20, 20);
  // Centre errors 0, 5 and 30 px, and a frame without an answer (never within any threshold).
  const std::vector<cv::Rect2d> truth = {box, box, box, box};
  const std::vector<cv::Rect2d> predicted = {box, {103, 104, 20, 20}, {130, 100, 20, 20}};
  const TrackingScores scores = ScoreTracking(predicted, truth);
  ASSERT_EQ(scores.precision.size(), 51u);
  ASSERT_EQ(PrecisionThresholds().size(), 51u);
  EXPECT_EQ(PrecisionThresholds()[50], 50.0);
  for (int t = 0; t <= 50; ++t) {
    const double expected = t < 5 ? 0.25 : t < 30 ? 0.5 : 0.75;
    EXPECT_DOUBLE_EQ(scores.precision[t], expected) << "threshold " << t << " px";
  }
  EXPECT_DOUBLE_EQ(scores.precision_20, scores.precision[20]);
  ASSERT_EQ(SuccessThresholds().size(), 21u);
  EXPECT_DOUBLE_EQ(SuccessThresholds()[7], 0.35);
  // No ground truth: the curve is there, all zeros.
  const TrackingScores none = ScoreTracking({box}, {cv::Rect2d()});
  EXPECT_EQ(none.precision, std::vector<double>(51, 0.0));
}
// ------------------------------------------------------------------------------------------
// tracks.csv

TEST(TracksCsv, RoundTripIsExact) {
  const TempDir dir;
  const std::vector<TrackRow> rows = {{0, 1, {10, 20, 30, 40}, "found"},
                                      {1, 1, {10.25, 20.125, 31, 39}, "occluded"},
                                      {1, 2, {0.1, 1.0 / 3.0, 7, 9}, "lost"}};
  WriteTracksCsv(dir.File("tracks.csv"), rows);
  const std::vector<TrackRow> read = ReadTracksCsv(dir.File("tracks.csv"));
  ASSERT_EQ(read.size(), rows.size());
  for (size_t i = 0; i < rows.size(); ++i) {
    EXPECT_EQ(read[i].frame, rows[i].frame);
    EXPECT_EQ(read[i].id, rows[i].id);
    EXPECT_EQ(read[i].box, rows[i].box);
    EXPECT_EQ(read[i].state, rows[i].state);
  }
}

TEST(TracksCsv, WritesTheHeaderAndIntegersAsIntegers) {
  const TempDir dir;
  WriteTracksCsv(dir.File("tracks.csv"), {{3, 2, {4, 5, 6, 7}, "found"}});
  std::ifstream in(dir.File("tracks.csv"));
  std::string header, row;
  std::getline(in, header);
  std::getline(in, row);
  EXPECT_EQ(header, "frame,id,x,y,w,h,state");
  EXPECT_EQ(row, "3,2,4,5,6,7,found");
}

TEST(TracksCsv, HeaderOnlyIsNoRows) {
  const TempDir dir;
  EXPECT_TRUE(ReadTracksCsv(dir.Write("t.csv", "frame,id,x,y,w,h,state\n\n")).empty());
}

TEST(TracksCsv, MalformedRowsNameFileAndLine) {
  const TempDir dir;
  const std::string header = "frame,id,x,y,w,h,state\n";
  struct Case {
    std::string text;
    std::string expected;
  };
  const std::vector<Case> cases = {
      {header + "0,1,2,3,4,5,found\n0,1,2,3,4,found\n", "t.csv:3: expected 7 fields"},
      {header + "0,1,2,x,4,5,found\n", "t.csv:2: field 'y' is not a number: 'x'"},
      {header + "0.5,1,2,3,4,5,found\n", "t.csv:2: field 'frame' is not an integer"},
      {header + "0,1,2,3,-4,5,found\n", "t.csv:2: w and h must be >= 0"},
      {header + "-1,1,2,3,4,5,found\n", "t.csv:2: frame number out of range: '-1' (must be in 0..1000000)"},
      {header + "0,1,2,3,4,5,hidden\n", "t.csv:2: state must be found, occluded or lost"},
      // A target's second row in one frame would be scored as another frame (issue 30).
      {header + "0,1,2,3,4,5,found\n0,2,2,3,4,5,found\n0,1,6,3,4,5,found\n",
       "t.csv:4: target 1 again in frame 0 (line 2 has it too)"},
      {"0,1,2,3,4,5,found\n", "t.csv:1: expected the header"},
      {"", "t.csv: empty"},
  };
  for (const Case& c : cases) {
    const std::string path = dir.Write("t.csv", c.text);
    const std::string message = InputErrorOf([&] { ReadTracksCsv(path); });
    EXPECT_NE(message.find(c.expected), std::string::npos) << c.text << " -> " << message;
  }
  EXPECT_NE(InputErrorOf([&] { ReadTracksCsv(dir.File("absent.csv")); }).find("absent.csv"),
            std::string::npos);
}

TEST(TracksCsv, UnwritablePathIsAnOutputError) {
  const TempDir dir;
  EXPECT_THROW(WriteTracksCsv(dir.File("no/such/folder/tracks.csv"), {}), OutputError);
}

// ------------------------------------------------------------------------------------------
// OTB ground truth

TEST(OtbGroundTruth, ReadsAnySeparatorAndConvertsToZeroBased) {
  const TempDir dir;
  const std::string path =
      dir.Write("groundtruth_rect.txt", "51\t52\t30\t40\n1,1,10,20\r\n3 4  5 6\n7, 8,\t9 ,10\n\n");
  const std::vector<cv::Rect2d> boxes = ReadOtbGroundTruth(path);
  ASSERT_EQ(boxes.size(), 4u);
  EXPECT_EQ(boxes[0], cv::Rect2d(50, 51, 30, 40));
  EXPECT_EQ(boxes[1], cv::Rect2d(0, 0, 10, 20));
  EXPECT_EQ(boxes[2], cv::Rect2d(2, 3, 5, 6));
  EXPECT_EQ(boxes[3], cv::Rect2d(6, 7, 9, 10));
}

TEST(OtbGroundTruth, ZeroSizeAndNanMeanNoBox) {
  const TempDir dir;
  const std::string path = dir.Write("gt.txt", "1 1 10 10\n0 0 0 0\nNaN NaN NaN NaN\n5 5 10 10\n");
  const std::vector<cv::Rect2d> boxes = ReadOtbGroundTruth(path);
  ASSERT_EQ(boxes.size(), 4u);
  EXPECT_EQ(boxes[1], cv::Rect2d());
  EXPECT_EQ(boxes[2], cv::Rect2d());
  EXPECT_EQ(ScoreTracking(boxes, boxes).frames, 2);
}

TEST(OtbGroundTruth, MalformedLinesNameFileAndLine) {
  const TempDir dir;
  struct Case {
    std::string text;
    std::string expected;
  };
  const std::vector<Case> cases = {
      {"1 1 10 10\n1 1 10\n", "gt.txt:2: expected 4 numbers"},
      {"1 1 10 10\n\n1 1 10 10\n", "gt.txt:2: expected 4 numbers 'x y w h', got 0 field(s)"},
      {"1 1 ten 10\n", "gt.txt:1: field 'w' is not a number"},
      {"1 1 10 -10\n", "gt.txt:1: w and h must be >= 0"},
      {"\n\n", "gt.txt: no boxes"},
  };
  for (const Case& c : cases) {
    const std::string path = dir.Write("gt.txt", c.text);
    const std::string message = InputErrorOf([&] { ReadOtbGroundTruth(path); });
    EXPECT_NE(message.find(c.expected), std::string::npos) << c.text << " -> " << message;
  }
}

}  // namespace
}  // namespace attend
