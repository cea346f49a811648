// The scanpath measures (eval/scanpath_metrics.h) on scanpaths built by hand, whose scores are
// worked out in the comments.
#include "eval/scanpath_metrics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace attend {
namespace {

// 1200 x 800 with the default 12 x 8 grid: cells of 100 x 100 px.
const cv::Size kGridImage(1200, 800);

// A fixation at the centre of cell (column, row) of kGridImage's grid.
Fixation InCell(int column, int row, double duration_s = 0.2) {
  Fixation f;
  f.x = 100.0 * column + 49.5;
  f.y = 100.0 * row + 49.5;
  f.duration_s = duration_s;
  return f;
}

Fixation FixationAt(double x, double y, double duration_s) {
  Fixation f;
  f.x = x;
  f.y = y;
  f.duration_s = duration_s;
  return f;
}

ScanMatchOptions WithThreshold(double threshold) {
  ScanMatchOptions options;
  options.threshold = threshold;
  return options;
}

TEST(ScanpathOptions, DefaultsAreValid) {
  std::string error;
  EXPECT_TRUE(ScanMatchOptions().Check(&error)) << error;
  EXPECT_TRUE(MultiMatchOptions().Check(&error)) << error;
  ScanMatchOptions bad;
  bad.threshold = 0.0;
  EXPECT_FALSE(bad.Check(&error));
  EXPECT_NE(error.find("threshold"), std::string::npos) << error;
  bad = ScanMatchOptions();
  bad.gap = 1.0;
  EXPECT_FALSE(bad.Check(&error));
  MultiMatchOptions bad_mm;
  bad_mm.direction_threshold_deg = 200.0;
  EXPECT_FALSE(bad_mm.Check(&error));
  EXPECT_NE(error.find("direction"), std::string::npos) << error;
}

TEST(GridCodes, CodeCellsRowMajorAndClampFixationsOutsideTheImage) {
  const Scanpath path = {InCell(0, 0), InCell(11, 7), InCell(3, 2), FixationAt(-10.0, 900.0, 0.2),
                         FixationAt(99.4, 0.0, 0.2), FixationAt(99.6, 0.0, 0.2)};
  EXPECT_EQ(GridCodes(path, kGridImage, {}), (std::vector<int>{0, 95, 27, 84, 0, 1}));
  // Another grid: 2 x 2 cells of 600 x 400.
  EXPECT_EQ(GridCodes(path, kGridImage, {2, 2}), (std::vector<int>{0, 3, 0, 2, 0, 0}));
}

TEST(ScanMatchThreshold, IsTwoStandardDeviationsOfTheAmplitudesInCells) {
  // Saccades of 1 cell right, then 3 cells down: amplitudes 1 and 3, mean 2, sd 1.
  const Scanpath path = {InCell(0, 0), InCell(1, 0), InCell(1, 3)};
  const std::vector<double> amplitudes = SaccadeAmplitudesInCells(path, kGridImage, {});
  ASSERT_EQ(amplitudes.size(), 2u);
  EXPECT_NEAR(amplitudes[0], 1.0, 1e-12);
  EXPECT_NEAR(amplitudes[1], 3.0, 1e-12);
  EXPECT_NEAR(ScanMatchThreshold(amplitudes), 2.0, 1e-12);
}

TEST(ScanMatch, SubstitutionIsTheThresholdLessTheDistanceBetweenCells) {
  const ScanMatchOptions options = WithThreshold(3.5);
  EXPECT_DOUBLE_EQ(ScanMatchSubstitution(0, 0, options), 3.5);
  EXPECT_DOUBLE_EQ(ScanMatchSubstitution(0, 12, options), 2.5);  // one row down
  EXPECT_DOUBLE_EQ(ScanMatchSubstitution(0, 3 + 12 * 4, options), -1.5);  // 3-4-5: 5 cells
  EXPECT_DOUBLE_EQ(ScanMatchSubstitution(3 + 12 * 4, 0, options), -1.5);
}

TEST(ScanMatch, IdenticalScanpathsScoreOne) {
  const Scanpath path = {InCell(2, 3), InCell(7, 1), InCell(7, 6), InCell(0, 0)};
  EXPECT_DOUBLE_EQ(ScanMatch(path, path, kGridImage, WithThreshold(3.5)), 1.0);
  ScanMatchOptions binned = WithThreshold(2.0);
  binned.temporal_bin_s = 0.05;
  EXPECT_DOUBLE_EQ(ScanMatch(path, path, kGridImage, binned), 1.0);
}

TEST(ScanMatch, SequencesOneCellApartScoreTheHandComputedAlignment) {
  // Each fixation of b one cell below a's: the best alignment pairs them in order, each pair
  // scoring 3.5 - 1 = 2.5 (no pair is closer than one cell), 7.5 over the maximum 3 x 3.5.
  const Scanpath a = {InCell(0, 0), InCell(1, 0), InCell(2, 0)};
  const Scanpath b = {InCell(0, 1), InCell(1, 1), InCell(2, 1)};
  const ScanMatchOptions options = WithThreshold(3.5);
  EXPECT_DOUBLE_EQ(
      NeedlemanWunschScore(GridCodes(a, kGridImage, {}), GridCodes(b, kGridImage, {}), options), 7.5);
  EXPECT_NEAR(ScanMatch(a, b, kGridImage, options), 7.5 / 10.5, 1e-12);
}

TEST(ScanMatch, GapsAlignScanpathsOfDifferentLengths) {
  // a = cells 0, 1, 2 of row 0; b = 0, 2. Best: 0-0 and 2-2 (3.5 each) with a's 1 against a
  // gap: 7 with gap 0 (2/3 of 3 x 3.5), 6 with gap -1. Aligning 1 with 0 or 2 instead gives
  // 3.5 + 2.5 = 6 at best, then a gap too.
  const Scanpath a = {InCell(0, 0), InCell(1, 0), InCell(2, 0)};
  const Scanpath b = {InCell(0, 0), InCell(2, 0)};
  ScanMatchOptions options = WithThreshold(3.5);
  EXPECT_NEAR(ScanMatch(a, b, kGridImage, options), 2.0 / 3.0, 1e-12);
  EXPECT_NEAR(ScanMatch(b, a, kGridImage, options), 2.0 / 3.0, 1e-12);
  options.gap = -1.0;
  EXPECT_DOUBLE_EQ(
      NeedlemanWunschScore(GridCodes(a, kGridImage, {}), GridCodes(b, kGridImage, {}), options), 6.0);
}

TEST(ScanMatch, AScanpathAgainstItsReverseKeepsOnlyItsMiddle) {
  // Cells 0, 5, 10 of row 0 against 10, 5, 0: only one pair can be aligned in order with a
  // positive score (5-5, or an end with the other's opposite end: 3.5 each); any second pair
  // is 5 or 10 cells apart. 3.5 / (3 x 3.5) = 1/3.
  const Scanpath path = {InCell(0, 0), InCell(5, 0), InCell(10, 0)};
  const Scanpath reversed(path.rbegin(), path.rend());
  EXPECT_NEAR(ScanMatch(path, reversed, kGridImage, WithThreshold(3.5)), 1.0 / 3.0, 1e-12);
  // Levenshtein: two substitutions (the ends) of three.
  EXPECT_NEAR(SequenceScore(path, reversed, kGridImage, {}), 1.0 / 3.0, 1e-12);
}

TEST(ScanMatch, TemporalBinsRepeatEachFixationPerBin) {
  // One fixation in the same cell, 100 ms against 200 ms: 2 and 4 letters with 50 ms bins;
  // the two align (2 x 3.5) and the longer sequence's maximum is 4 x 3.5: 0.5.
  const Scanpath a = {InCell(4, 4, 0.1)};
  const Scanpath b = {InCell(4, 4, 0.2)};
  ScanMatchOptions options = WithThreshold(3.5);
  EXPECT_DOUBLE_EQ(ScanMatch(a, b, kGridImage, options), 1.0);  // no bins: durations do not count
  options.temporal_bin_s = 0.05;
  EXPECT_EQ(ScanMatchSequence(b, kGridImage, options), (std::vector<int>{52, 52, 52, 52}));
  EXPECT_DOUBLE_EQ(ScanMatch(a, b, kGridImage, options), 0.5);
  // A fixation shorter than half a bin still counts once.
  EXPECT_EQ(ScanMatchSequence({InCell(0, 0, 0.01)}, kGridImage, options).size(), 1u);
}

TEST(SequenceScore, LevenshteinKnownCases) {
  // kitten -> sitting: 3 (k->s, e->i, insert g).
  const std::vector<int> kitten = {'k', 'i', 't', 't', 'e', 'n'};
  const std::vector<int> sitting = {'s', 'i', 't', 't', 'i', 'n', 'g'};
  EXPECT_EQ(CodeEditDistance(kitten, sitting), 3);
  EXPECT_EQ(CodeEditDistance(sitting, kitten), 3);
  EXPECT_EQ(CodeEditDistance({}, {1, 2, 3}), 3);
  EXPECT_EQ(CodeEditDistance({1, 2, 3}, {1, 3}), 1);
  EXPECT_EQ(CodeEditDistance({1, 2, 3}, {1, 2, 3}), 0);
  EXPECT_EQ(CodeEditDistance({1, 2}, {2, 1}), 2);
}

TEST(SequenceScore, IsOneLessTheDistanceOverTheLongerLength) {
  const Scanpath a = {InCell(0, 0), InCell(1, 0), InCell(2, 0), InCell(3, 0)};
  const Scanpath b = {InCell(0, 0), InCell(2, 0)};  // two deletions
  EXPECT_DOUBLE_EQ(SequenceScore(a, a, kGridImage, {}), 1.0);
  EXPECT_DOUBLE_EQ(SequenceScore(a, b, kGridImage, {}), 0.5);
  EXPECT_DOUBLE_EQ(SequenceScore(b, a, kGridImage, {}), 0.5);
}

TEST(MultiMatch, IdenticalScanpathsScoreOneInEveryDimension) {
  const Scanpath path = {FixationAt(100, 100, 0.2), FixationAt(700, 150, 0.35), FixationAt(650, 600, 0.15),
                         FixationAt(200, 500, 0.3)};
  for (const bool simplify : {false, true}) {
    MultiMatchOptions options;
    options.simplify = simplify;
    const std::optional<MultiMatchScores> s = MultiMatch(path, path, kGridImage, options);
    ASSERT_TRUE(s.has_value());
    EXPECT_DOUBLE_EQ(s->shape, 1.0);
    EXPECT_DOUBLE_EQ(s->direction, 1.0);
    EXPECT_DOUBLE_EQ(s->length, 1.0);
    EXPECT_DOUBLE_EQ(s->position, 1.0);
    EXPECT_DOUBLE_EQ(s->duration, 1.0);
  }
}

TEST(MultiMatch, HandBuiltScanpathsScoreTheHandComputedValues) {
  // On 1000 x 1000 (diagonal 1000 sqrt 2):
  //   a: (100,100) 0.2 s -> (400,100) 0.3 s -> (400,500): saccades (300,0), (0,400)
  //   b: (100,200) 0.2 s -> (500,200) 0.1 s -> (600,500): saccades (400,0), (100,300)
  // Vector differences: [0][0] 100, [0][1] |(200,-300)| = 360.6, [1][0] |(-400,400)| = 565.7,
  // [1][1] |(-100,100)| = 141.4: the cheapest path is the diagonal, pairs (0,0) and (1,1).
  const cv::Size image(1000, 1000);
  const double diagonal = 1000.0 * std::sqrt(2.0);
  const Scanpath a = {FixationAt(100, 100, 0.2), FixationAt(400, 100, 0.3), FixationAt(400, 500, 0.2)};
  const Scanpath b = {FixationAt(100, 200, 0.2), FixationAt(500, 200, 0.1), FixationAt(600, 500, 0.4)};
  const std::vector<std::pair<int, int>> pairs = AlignSaccades(SaccadeVectors(a), SaccadeVectors(b));
  EXPECT_EQ(pairs, (std::vector<std::pair<int, int>>{{0, 0}, {1, 1}}));
  const std::optional<MultiMatchScores> s = MultiMatch(a, b, image, {});
  ASSERT_TRUE(s.has_value());
  // Medians of two values are their means.
  const double shape = (100.0 + 100.0 * std::sqrt(2.0)) / 2.0;
  EXPECT_NEAR(s->shape, 1.0 - shape / (2.0 * diagonal), 1e-12);
  // Directions: 0 and 0; pi/2 and atan2(300, 100).
  const double direction = (std::numbers::pi / 2.0 - std::atan2(300.0, 100.0)) / 2.0;
  EXPECT_NEAR(s->direction, 1.0 - direction / std::numbers::pi, 1e-12);
  // Lengths: 300 and 400; 400 and sqrt(100000) = 316.2.
  const double length = (100.0 + (400.0 - std::sqrt(100000.0))) / 2.0;
  EXPECT_NEAR(s->length, 1.0 - length / diagonal, 1e-12);
  // Start fixations: (100,100)-(100,200) = 100; (400,100)-(500,200) = 141.4.
  EXPECT_NEAR(s->position, 1.0 - shape / diagonal, 1e-12);
  // Durations of the start fixations: 0.2 and 0.2 (0); 0.3 and 0.1 (0.2 / 0.3).
  EXPECT_NEAR(s->duration, 1.0 - (0.0 + 2.0 / 3.0) / 2.0, 1e-12);
}

TEST(MultiMatch, AScanpathAgainstItsReverse) {
  // Cells 0, 5, 10 of row 0 (x = 49.5, 549.5, 1049.5) against the reverse: saccades (500, 0)
  // twice against (-500, 0) twice, every difference 1000, pairs (0,0), (1,1). Shape
  // 1 - 1000 / (2 x 1442.2); direction 0 (opposite); length 1; positions 1000 and 0, median 500;
  // durations equal.
  const Scanpath path = {InCell(0, 0), InCell(5, 0), InCell(10, 0)};
  const Scanpath reversed(path.rbegin(), path.rend());
  const double diagonal = std::hypot(1200.0, 800.0);
  const std::optional<MultiMatchScores> s = MultiMatch(path, reversed, kGridImage, {});
  ASSERT_TRUE(s.has_value());
  EXPECT_NEAR(s->shape, 1.0 - 1000.0 / (2.0 * diagonal), 1e-12);
  EXPECT_NEAR(s->direction, 0.0, 1e-12);
  EXPECT_NEAR(s->length, 1.0, 1e-12);
  EXPECT_NEAR(s->position, 1.0 - 500.0 / diagonal, 1e-12);
  EXPECT_NEAR(s->duration, 1.0, 1e-12);
}

TEST(MultiMatch, EachDimensionIsTheMedianOverTheAlignedPairsNotTheMean) {
  // Three saccades of (200, 0) against (200, 0), (200, 0), (200, 300): pairs (0,0), (1,1),
  // (2,2) with shape differences 0, 0, 300. The median is 0, so shape, direction and length
  // are 1 (a mean would give 1 - 100 / (2 x diagonal) for shape).
  const Scanpath a = {FixationAt(100, 100, 0.2), FixationAt(300, 100, 0.2), FixationAt(500, 100, 0.2), FixationAt(700, 100, 0.2)};
  Scanpath b = a;
  b[3].y = 400;
  EXPECT_EQ(AlignSaccades(SaccadeVectors(a), SaccadeVectors(b)),
            (std::vector<std::pair<int, int>>{{0, 0}, {1, 1}, {2, 2}}));
  const std::optional<MultiMatchScores> s = MultiMatch(a, b, kGridImage, {});
  ASSERT_TRUE(s.has_value());
  EXPECT_DOUBLE_EQ(s->shape, 1.0);
  EXPECT_DOUBLE_EQ(s->direction, 1.0);
  EXPECT_DOUBLE_EQ(s->length, 1.0);
  EXPECT_DOUBLE_EQ(s->position, 1.0);
}

TEST(MultiMatch, TheAlignmentTakesTheCheapestPathAndPairsDifferentLengths) {
  // a: (100,0), (0,100); b: (100,0), (60,40), (0,100). Differences: [0][1] = 56.6,
  // [1][1] = 84.9, [0][2] = [1][0] = 141.4, [0][0] = [1][2] = 0: through [0][1] (56.6) is
  // cheaper than through [1][1] (84.9).
  const std::vector<Saccade> a = {{0, 0, 100, 0, 0.2}, {100, 0, 0, 100, 0.2}};
  const std::vector<Saccade> b = {{0, 0, 100, 0, 0.2}, {100, 0, 60, 40, 0.2}, {160, 40, 0, 100, 0.2}};
  EXPECT_EQ(AlignSaccades(a, b), (std::vector<std::pair<int, int>>{{0, 0}, {0, 1}, {1, 2}}));
  EXPECT_EQ(AlignSaccades(b, a), (std::vector<std::pair<int, int>>{{0, 0}, {1, 0}, {2, 1}}));
  // One saccade against three: every one of them is paired with it.
  EXPECT_EQ(AlignSaccades({a[0]}, b), (std::vector<std::pair<int, int>>{{0, 0}, {0, 1}, {0, 2}}));
}

TEST(MultiMatch, NeedsASaccadeInEachScanpathAndKnownDurationsForDuration) {
  const Scanpath one = {FixationAt(10, 10, 0.2)};
  const Scanpath two = {FixationAt(10, 10, 0.2), FixationAt(500, 300, 0.2)};
  EXPECT_FALSE(MultiMatch(one, two, kGridImage, {}).has_value());
  EXPECT_FALSE(MultiMatch(two, one, kGridImage, {}).has_value());
  Scanpath unknown = two;
  for (Fixation& f : unknown) f.duration_s = -1.0;
  const std::optional<MultiMatchScores> s = MultiMatch(two, unknown, kGridImage, {});
  ASSERT_TRUE(s.has_value());
  EXPECT_DOUBLE_EQ(s->position, 1.0);
  EXPECT_TRUE(std::isnan(s->duration));
}

TEST(MultiMatch, SimplificationMergesSaccadesInOneDirectionOrShortOnes) {
  MultiMatchOptions options;  // 45 degrees, 0.1 x diagonal (144 px here), 0.3 s
  // Three saccades to the right with short fixations between them: one saccade (300, 0).
  const Scanpath straight = {FixationAt(0, 0, 0.1), FixationAt(100, 0, 0.1), FixationAt(200, 10, 0.1), FixationAt(300, 0, 0.1)};
  std::vector<Saccade> merged = SimplifySaccades(SaccadeVectors(straight), kGridImage, options);
  ASSERT_EQ(merged.size(), 1u);
  EXPECT_DOUBLE_EQ(merged[0].dx, 300.0);
  EXPECT_DOUBLE_EQ(merged[0].dy, 0.0);
  EXPECT_DOUBLE_EQ(merged[0].duration_s, 0.1);
  // The same with long fixations between them: nothing merges.
  Scanpath slow = straight;
  for (Fixation& f : slow) f.duration_s = 0.5;
  EXPECT_EQ(SimplifySaccades(SaccadeVectors(slow), kGridImage, options).size(), 3u);
  // Two short saccades at a right angle: merged by amplitude into (20, 30).
  const Scanpath small = {FixationAt(500, 500, 0.1), FixationAt(520, 500, 0.1), FixationAt(520, 530, 0.1)};
  merged = SimplifySaccades(SaccadeVectors(small), kGridImage, options);
  ASSERT_EQ(merged.size(), 1u);
  EXPECT_DOUBLE_EQ(merged[0].dx, 20.0);
  EXPECT_DOUBLE_EQ(merged[0].dy, 30.0);
  // Long saccades at a right angle stay two.
  const Scanpath corner = {FixationAt(100, 100, 0.1), FixationAt(600, 100, 0.1), FixationAt(600, 700, 0.1)};
  EXPECT_EQ(SimplifySaccades(SaccadeVectors(corner), kGridImage, options).size(), 2u);
}

}  // namespace
}  // namespace attend
