// The row check (stereo/row_check.h) on pairs whose rows are known by construction.
#include "stereo/row_check.h"

#include <gtest/gtest.h>

#include "tests/support/stereo_pair_maker.h"

namespace attend {
namespace {

TEST(RowCheck, RectifiedPairMeasuresNoOffset) {
  const testing::KnownPair pair = testing::MakeKnownPair({640, 480}, 12.0);
  const RowCheck check = MeasureRowOffset(pair.rectified_left, pair.rectified_right);
  EXPECT_TRUE(check.Decided());
  EXPECT_GT(check.matches, 100);
  EXPECT_LT(check.row_offset_px, 0.2);
}

TEST(RowCheck, MeasuresAVerticalShift) {
  const testing::KnownPair pair = testing::MakeKnownPair({640, 480}, 12.0);
  for (double rows : {0.5, 1.5, 3.0}) {
    const RowCheck check =
        MeasureRowOffset(pair.rectified_left, testing::ShiftDown(pair.rectified_right, rows));
    EXPECT_TRUE(check.Decided());
    EXPECT_NEAR(check.row_offset_px, rows, 0.15) << rows;
    EXPECT_NEAR(check.row_shift_px, rows, 0.15) << rows;
  }
}

TEST(RowCheck, RefusesShiftedTurnedAndRawPairs) {
  const testing::KnownPair pair = testing::MakeKnownPair({640, 480}, 12.0);
  const RowCheck shifted =
      MeasureRowOffset(pair.rectified_left, testing::ShiftDown(pair.rectified_right, 3.0));
  const RowCheck turned =
      MeasureRowOffset(pair.rectified_left, testing::Rotate(pair.rectified_right, 1.0));
  const RowCheck raw = MeasureRowOffset(pair.raw_left, pair.raw_right);
  for (const RowCheck& check : {shifted, turned, raw}) {
    EXPECT_TRUE(check.Decided());
    EXPECT_GT(check.row_offset_px, kMaxRowOffsetPx);
  }
}

TEST(RowCheck, BlankViewsGiveNoVerdict) {
  const cv::Mat grey(240, 320, CV_8UC3, cv::Scalar(90, 90, 90));
  const RowCheck check = MeasureRowOffset(grey, grey);
  EXPECT_FALSE(check.Decided());
  EXPECT_EQ(MeasureRowOffset(grey, cv::Mat()).matches, 0);
}

}  // namespace
}  // namespace attend
