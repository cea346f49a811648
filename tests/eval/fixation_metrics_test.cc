#include "eval/fixation_metrics.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <opencv2/imgproc.hpp>
#include <random>

#include "tests/support/error_message.h"
#include "util/error.h"

namespace attend {
namespace {

using testing::ConfigErrorOf;
using testing::InputErrorOf;

const cv::Size kSize(50, 40);  // width x height

// A fixation at 0-based pixel (col, row).
Fixation At(double col, double row, int subject = 0) { return {subject, col, row}; }

std::vector<Fixation> FewFixations() {
  return {At(10, 12), At(11, 13, 1), At(35, 30), At(42, 8, 2), At(25, 20, 3)};
}

cv::Mat Values(int rows, int cols, const std::vector<double>& values) {
  return cv::Mat(rows, cols, CV_64F, const_cast<double*>(values.data())).clone();
}

// A smooth map with seeded noise: every pixel distinct, not related to any fixation.
cv::Mat RandomMap(uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> noise(0.0, 1.0);
  cv::Mat map(kSize, CV_64F);
  for (int r = 0; r < map.rows; ++r) {
    for (int c = 0; c < map.cols; ++c)
      map.at<double>(r, c) = std::sin(0.2 * c + 0.1 * r) + noise(rng);
  }
  return map;
}

// `count` fixations from a Gaussian around the image centre: a pure centre bias.
std::vector<Fixation> CentreBiasedFixations(cv::Size size, int count, double fraction,
                                            uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> x((size.width - 1) / 2.0, fraction * size.width);
  std::normal_distribution<double> y((size.height - 1) / 2.0, fraction * size.height);
  std::vector<Fixation> out;
  for (int i = 0; i < count; ++i) out.push_back(At(x(rng), y(rng), i % 15));
  return out;
}

TEST(FixationDensity, SumsToOneAndPeaksAtAnIsolatedFixation) {
  const cv::Mat density = FixationDensity(kSize, {At(10, 12), At(40, 30), At(-3, 5)}, 2.0);
  ASSERT_EQ(density.type(), CV_64F);
  ASSERT_EQ(density.size(), kSize);
  EXPECT_NEAR(cv::sum(density)[0], 1.0, 1e-12);
  const double peak = density.at<double>(12, 10);
  for (int dr = -1; dr <= 1; ++dr) {
    for (int dc = -1; dc <= 1; ++dc) {
      if (dr == 0 && dc == 0) continue;
      EXPECT_GT(peak, density.at<double>(12 + dr, 10 + dc)) << dr << " " << dc;
    }
  }
  cv::Point max_at;
  cv::minMaxLoc(density, nullptr, nullptr, nullptr, &max_at);
  EXPECT_TRUE(max_at == cv::Point(10, 12) || max_at == cv::Point(40, 30)) << max_at;
}

TEST(FixationDensity, EqualsAGaussianBlurOfTheCountMap) {
  const std::vector<Fixation> fixations = {At(1, 2),   At(1, 2),   At(30.4, 2),
                                           At(48, 39), At(20, 20), At(80, 3)};
  cv::Mat counts(kSize, CV_64F, cv::Scalar(0.0));
  counts.at<double>(2, 1) = 2.0;
  counts.at<double>(2, 30) = 1.0;
  counts.at<double>(39, 48) = 1.0;
  counts.at<double>(20, 20) = 1.0;
  for (double sigma : {0.8, 3.0, 30.0}) {  // the last one's kernel is wider than the map
    cv::Mat blurred;
    cv::GaussianBlur(counts, blurred, cv::Size(0, 0), sigma, sigma, cv::BORDER_CONSTANT);
    blurred /= cv::sum(blurred)[0];
    EXPECT_LT(cv::norm(FixationDensity(kSize, fixations, sigma), blurred, cv::NORM_INF), 1e-15)
        << sigma;
  }
}

TEST(FixationDensity, CountsDuplicateFixations) {
  const cv::Mat density = FixationDensity(kSize, {At(10, 12), At(10, 12), At(40, 30)}, 2.0);
  EXPECT_NEAR(density.at<double>(12, 10) / density.at<double>(30, 40), 2.0, 1e-9);
}

TEST(FixationDensity, NoFixationInsideIsAnError) {
  EXPECT_NE(InputErrorOf([] {
              FixationDensity(kSize, {At(50, 0), At(0, -1)}, 2.0);
            }).find("no fixation falls inside the 50x40"),
            std::string::npos);
}

TEST(FixationMetrics, MapEqualToTheDensityIsPerfect) {
  const cv::Mat density = FixationDensity(kSize, FewFixations(), 3.0);
  EXPECT_NEAR(Cc(density, density), 1.0, 1e-12);
  EXPECT_NEAR(Sim(density, density), 1.0, 1e-12);
  EXPECT_NEAR(Kl(density, density), 0.0, 1e-9);
  // A worse map scores worse on each.
  const cv::Mat other = RandomMap(3);
  EXPECT_LT(Cc(other, density), 0.5);
  EXPECT_LT(Sim(other, density), 0.9);
  EXPECT_GT(Kl(other, density), 0.1);
}

TEST(FixationMetrics, ConstantMapIsChance) {
  const cv::Mat constant(kSize, CV_32F, cv::Scalar(0.7));
  EXPECT_DOUBLE_EQ(Nss(constant, FewFixations()), 0.0);
  EXPECT_NEAR(AucJudd(constant, FewFixations()), 0.5, 1e-12);
  EXPECT_NEAR(AucBorji(constant, FewFixations()), 0.5, 1e-12);
  EXPECT_DOUBLE_EQ(Cc(constant, FixationDensity(kSize, FewFixations(), 3.0)), 0.0);
}

TEST(AucJudd, MapThatIsOneExactlyAtTheFixationsIsPerfect) {
  // Fractional coordinates round to the nearest pixel: 10.4 -> 10, 12.6 -> 13.
  const std::vector<Fixation> fixations = {At(10.4, 12.6), At(30, 5), At(44.5, 33), At(0, 0)};
  cv::Mat map(kSize, CV_64F, cv::Scalar(0.0));
  for (const cv::Point& p :
       {cv::Point(10, 13), cv::Point(30, 5), cv::Point(45, 33), cv::Point(0, 0)}) {
    map.at<double>(p) = 1.0;
  }
  EXPECT_NEAR(AucJudd(map, fixations), 1.0, 1e-9);
  // Off by one pixel, the fixations land on zeros: half the fixations tie with the negatives.
  std::vector<Fixation> shifted;
  for (const Fixation& f : fixations) shifted.push_back(At(f.x, f.y + 1.0));
  EXPECT_LT(AucJudd(map, shifted), 0.6);
}

TEST(AucJudd, LinksTheVerticesAtFixationThresholdsAsTheMitCode) {
  // Values 0.1 0.4 0.5 0.8, fixated 0.4 and 0.8. Thresholds 0.8: tp 1/2, fp 0/2; 0.4: tp 1,
  // fp 1/2 (0.5 is a negative above it). Trapezoids over (0,0) (0,.5) (.5,1) (1,1):
  // 0 + 0.5 x 0.75 + 0.5 x 1 = 0.875 (the rank statistic would say 0.75).
  const cv::Mat map = Values(1, 4, {0.1, 0.4, 0.5, 0.8});
  EXPECT_NEAR(AucJudd(map, {At(1, 0), At(3, 0)}), 0.875, 1e-12);
}

TEST(Nss, HandComputedCase) {
  // [0 0; 0 4]: mean 1, population sd sqrt((1 + 1 + 1 + 9) / 4) = sqrt(3). At (1, 1) the z-score
  // is 3 / sqrt(3) = sqrt(3); at (0, 0) it is -1 / sqrt(3), so both give 1 / sqrt(3).
  const cv::Mat map = Values(2, 2, {0, 0, 0, 4});
  EXPECT_NEAR(Nss(map, {At(1, 1)}), std::sqrt(3.0), 1e-12);
  EXPECT_NEAR(Nss(map, {At(1, 1), At(0, 0)}), 1.0 / std::sqrt(3.0), 1e-12);
  // Outside fixations are dropped and a pixel fixated twice counts once.
  EXPECT_NEAR(Nss(map, {At(1, 1), At(0, 0), At(0.2, -0.1), At(2, 0), At(-1, 1)}),
              1.0 / std::sqrt(3.0), 1e-12);
}

TEST(FixationMetrics, PermutedMapScoresWorse) {
  const std::vector<Fixation> fixations = FewFixations();
  const cv::Mat map = FixationDensity(kSize, fixations, 3.0);
  cv::Mat permuted = map.clone();
  double* begin = permuted.ptr<double>(0);
  std::shuffle(begin, begin + permuted.total(), std::mt19937_64(5));
  EXPECT_GT(Nss(map, fixations), Nss(permuted, fixations) + 1.0);
  EXPECT_GT(AucJudd(map, fixations), AucJudd(permuted, fixations) + 0.2);
  EXPECT_GT(Cc(map, map), Cc(permuted, map) + 0.5);
}

TEST(FixationMetrics, NssAucJuddAndCcIgnoreAPositiveAffineChange) {
  const std::vector<Fixation> fixations = CentreBiasedFixations(kSize, 40, 0.2, 11);
  const cv::Mat map = RandomMap(7);
  const cv::Mat changed = 3.5 * map - 2.0;
  const cv::Mat density = FixationDensity(kSize, fixations, 3.0);
  EXPECT_NEAR(Nss(changed, fixations), Nss(map, fixations), 1e-9);
  EXPECT_NEAR(AucJudd(changed, fixations), AucJudd(map, fixations), 1e-12);
  EXPECT_NEAR(Cc(changed, density), Cc(map, density), 1e-12);
  // A negative factor is not such a change.
  EXPECT_NEAR(Nss(-map, fixations), -Nss(map, fixations), 1e-9);
}

TEST(FixationMetrics, FloatAndDoubleMapsScoreAlike) {
  const std::vector<Fixation> fixations = FewFixations();
  const cv::Mat map = RandomMap(9);
  cv::Mat as_float;
  map.convertTo(as_float, CV_32F);
  cv::Mat back;
  as_float.convertTo(back, CV_64F);  // the values a float map holds
  EXPECT_DOUBLE_EQ(Nss(as_float, fixations), Nss(back, fixations));
  EXPECT_DOUBLE_EQ(AucJudd(as_float, fixations), AucJudd(back, fixations));
}

TEST(AucBorji, DeterministicForASeed) {
  const std::vector<Fixation> fixations = CentreBiasedFixations(kSize, 30, 0.2, 2);
  const cv::Mat map = RandomMap(4);
  EXPECT_EQ(AucBorji(map, fixations, 20, 0.1, 7), AucBorji(map, fixations, 20, 0.1, 7));
  EXPECT_NE(AucBorji(map, fixations, 20, 0.1, 7), AucBorji(map, fixations, 20, 0.1, 8));
  // A map peaked at the fixations is far above chance.
  EXPECT_GT(AucBorji(FixationDensity(kSize, fixations, 2.0), fixations), 0.85);
}

TEST(ShuffledAuc, DeterministicForASeed) {
  const std::vector<Fixation> fixations = CentreBiasedFixations(kSize, 30, 0.2, 2);
  const std::vector<Fixation> others = CentreBiasedFixations(kSize, 300, 0.2, 3);
  const cv::Mat map = RandomMap(4);
  EXPECT_EQ(ShuffledAuc(map, fixations, others, 20, 0.1, 7),
            ShuffledAuc(map, fixations, others, 20, 0.1, 7));
  EXPECT_NE(ShuffledAuc(map, fixations, others, 20, 0.1, 7),
            ShuffledAuc(map, fixations, others, 20, 0.1, 8));
}

TEST(ShuffledAuc, CentreBiasIsChanceAgainstCentreBiasedFixations) {
  // Large enough that few of the others' fixations share a pixel: the others count once per
  // pixel, so a crowded centre would be under-sampled and the bias not cancelled.
  const cv::Size size(400, 300);
  const std::vector<Fixation> fixations = CentreBiasedFixations(size, 200, 0.15, 21);
  const std::vector<Fixation> others = CentreBiasedFixations(size, 2000, 0.15, 22);
  const cv::Mat centre = CentreBias(size, 0.15);
  EXPECT_GT(AucJudd(centre, fixations), 0.75);
  EXPECT_NEAR(ShuffledAuc(centre, fixations, others), 0.5, 0.05);
  // A map that knows where these fixations are still beats the shuffled negatives.
  EXPECT_GT(ShuffledAuc(FixationDensity(size, fixations, 1.0), fixations, others), 0.7);
}

TEST(InformationGain, BaselineGainsNothingAndAPeakedMapGains) {
  const std::vector<Fixation> fixations = CentreBiasedFixations(kSize, 40, 0.15, 31);
  const cv::Mat baseline = CentreBias(kSize);
  EXPECT_DOUBLE_EQ(InformationGain(baseline, baseline, fixations), 0.0);
  EXPECT_GT(InformationGain(FixationDensity(kSize, fixations, 2.0), baseline, fixations), 0.5);
  // A uniform map knows less than the centre bias about centre-biased fixations.
  EXPECT_LT(InformationGain(cv::Mat(kSize, CV_64F, cv::Scalar(1.0)), baseline, fixations), 0.0);
}

TEST(InformationGain, AConstantMapWithRoundingNoiseIsTheConstantMap) {
  // A constant float map resized for scoring comes back with differences in its last bits; those
  // are no structure: the same IG as the constant map (it was NaN once, for a tiny constant).
  const std::vector<Fixation> fixations = CentreBiasedFixations(kSize, 40, 0.15, 37);
  const cv::Mat baseline = CentreBias(kSize);
  for (const double level : {1.0, 1.8626451e-09}) {
    cv::Mat noisy(kSize, CV_64F, cv::Scalar(level));
    noisy.at<double>(3, 4) = std::nextafter(level, 2.0);
    noisy.at<double>(7, 1) = std::nextafter(level, 0.0);
    const double ig = InformationGain(noisy, baseline, fixations);
    ASSERT_TRUE(std::isfinite(ig)) << level;
    EXPECT_NEAR(ig, InformationGain(cv::Mat(kSize, CV_64F, cv::Scalar(level)), baseline, fixations),
                1e-9)
        << level;
  }
}

TEST(CentreBias, PeaksAtTheCentreWithTheRequestedSpread) {
  const cv::Mat bias = CentreBias(cv::Size(101, 51), 0.25);
  ASSERT_EQ(bias.type(), CV_64F);
  EXPECT_DOUBLE_EQ(bias.at<double>(25, 50), 1.0);
  // sigma_x = 0.25 x 101 = 25.25 px along the centre row; sigma_y = 0.25 x 51 = 12.75 px.
  EXPECT_NEAR(bias.at<double>(25, 100), std::exp(-0.5 * std::pow(50.0 / 25.25, 2)), 1e-12);
  EXPECT_NEAR(bias.at<double>(0, 50), std::exp(-0.5 * std::pow(25.0 / 12.75, 2)), 1e-12);
}

TEST(MeanWithInterval, UsesTheSampleStandardDeviation) {
  const MeanInterval interval = MeanWithInterval({1, 2, 3, 4});
  // sd = sqrt(((1.5^2 + 0.5^2) x 2) / 3) = sqrt(5 / 3); half width 1.96 sd / sqrt(4).
  const double half = 1.96 * std::sqrt(5.0 / 3.0) / 2.0;
  EXPECT_EQ(interval.n, 4);
  EXPECT_DOUBLE_EQ(interval.mean, 2.5);
  EXPECT_NEAR(interval.low, 2.5 - half, 1e-12);
  EXPECT_NEAR(interval.high, 2.5 + half, 1e-12);
  const MeanInterval one = MeanWithInterval({3});
  EXPECT_EQ(one.low, 3.0);
  EXPECT_EQ(one.high, 3.0);
}

TEST(FixationMetrics, BadMapsAreInputErrors) {
  const cv::Mat map = RandomMap(1);
  EXPECT_NE(InputErrorOf([&] {
              Cc(map, cv::Mat(kSize.height, kSize.width + 1, CV_64F, cv::Scalar(0.0)));
            }).find("CC: the maps differ in size (50x40 and 51x40)"),
            std::string::npos);
  EXPECT_NE(InputErrorOf([] { Nss(cv::Mat(), FewFixations()); }).find("NSS: the map is empty"),
            std::string::npos);
  EXPECT_NE(InputErrorOf([] {
              AucJudd(cv::Mat(kSize, CV_8U, cv::Scalar(1)), FewFixations());
            }).find("one-channel CV_32F or CV_64F"),
            std::string::npos);
  EXPECT_NE(InputErrorOf([&] {
              AucJudd(map, {At(60, 1), At(1, 45)});
            }).find("no fixation falls"),
            std::string::npos);
  cv::Mat with_nan = map.clone();
  with_nan.at<double>(3, 3) = std::nan("");
  EXPECT_NE(InputErrorOf([&] { Nss(with_nan, FewFixations()); }).find("non-finite"),
            std::string::npos);
}

TEST(ScoreMap, EqualsTheSingleMetricsAndIteratesByName) {
  const std::vector<Fixation> fixations = CentreBiasedFixations(kSize, 30, 0.2, 41);
  const std::vector<Fixation> others = CentreBiasedFixations(kSize, 300, 0.2, 42);
  const cv::Mat map = RandomMap(43);
  const cv::Mat density = FixationDensity(kSize, fixations, 2.0);
  const cv::Mat baseline = CentreBias(kSize);
  const FixationScores scores = ScoreMap(map, fixations, others, density, baseline);
  const std::vector<double> expected = {
      Nss(map, fixations),      AucJudd(map, fixations),
      AucBorji(map, fixations), ShuffledAuc(map, fixations, others),
      Cc(map, density),         Kl(map, density),
      Sim(map, density),        InformationGain(map, baseline, fixations)};
  const std::vector<std::string> names = {"nss", "auc_judd", "auc_borji", "sauc",
                                          "cc",  "kl",       "sim",       "ig"};
  ASSERT_EQ(FixationMetricNames(), names);
  for (size_t i = 0; i < names.size(); ++i)
    EXPECT_EQ(Get(scores, names[i]), expected[i]) << names[i];
  // Every metric is computed (none left at its default).
  for (const std::string& name : names) EXPECT_NE(Get(scores, name), 0.0) << name;
  EXPECT_NE(ConfigErrorOf([&] { Get(scores, "sacu"); }).find("did you mean 'sauc'"),
            std::string::npos);
  EXPECT_NE(InputErrorOf([&] {
              ScoreMap(map, fixations, others, density, CentreBias({10, 10}));
            }).find("baseline"),
            std::string::npos);
}

}  // namespace
}  // namespace attend
