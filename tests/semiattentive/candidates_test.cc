// The candidates of the attention stage (semiattentive/candidates.h) on saliency maps drawn with
// blocks of known saliency, and the colour regions under them.
#include "semiattentive/candidates.h"

#include <gtest/gtest.h>

namespace attend {
namespace {

TEST(CandidateFinder, RanksTheSalientRegionsByMeanTimesAreaAndDropsTheSmallAndTheDim) {
  cv::Mat saliency = cv::Mat::zeros(80, 100, CV_32FC1);
  saliency(cv::Rect(10, 10, 20, 20)).setTo(0.8f);  // 400 px: 320
  saliency(cv::Rect(50, 40, 30, 20)).setTo(0.6f);  // 600 px: 360
  saliency(cv::Rect(85, 5, 8, 8)).setTo(0.9f);     // 64 px: under min_area
  saliency(cv::Rect(10, 60, 30, 15)).setTo(0.1f);  // under min_saliency
  SelectOptions options;                           // min_saliency 0.2, min_area 120
  CandidateFinder finder(options);
  const Candidates c = finder.Find(saliency);
  ASSERT_EQ(c.ranked.size(), 2u);
  const int first = c.ranked[0].second, second = c.ranked[1].second;
  EXPECT_EQ(c.Box(first), cv::Rect(50, 40, 30, 20));
  EXPECT_EQ(c.area[first], 600);
  EXPECT_NEAR(c.ranked[0].first, 360.0, 1e-3);
  EXPECT_EQ(c.Box(second), cv::Rect(10, 10, 20, 20));
  EXPECT_NEAR(c.ranked[1].first, 320.0, 1e-3);
  // The most salient pixel: the first of the block in row order.
  EXPECT_EQ(c.peak[second], cv::Point(10, 10));
  EXPECT_FLOAT_EQ(c.peak_value[second], 0.8f);
  EXPECT_EQ(c.labels.at<int>(15, 15), second);
}

TEST(CandidateFinder, AMapWithNothingSalientHasNoCandidates) {
  CandidateFinder finder{SelectOptions()};
  EXPECT_TRUE(finder.Find(cv::Mat::zeros(40, 40, CV_32FC1)).ranked.empty());
}

TEST(RankCandidates, OrdersByMassPeakOrMeanThenNearnessThenFaces) {
  // Three blocks: a large dim one (mass 0.4 x 1200 = 480), a small bright one (0.9 x 144 =
  // 129.6) and a middling one (0.6 x 400 = 240).
  cv::Mat saliency = cv::Mat::zeros(100, 200, CV_32FC1);
  saliency(cv::Rect(0, 0, 40, 30)).setTo(0.4f);
  saliency(cv::Rect(180, 80, 12, 12)).setTo(0.9f);
  saliency(cv::Rect(90, 40, 20, 20)).setTo(0.6f);
  SelectOptions options;
  CandidateFinder finder(options);
  const Candidates found = finder.Find(saliency);
  ASSERT_EQ(found.ranked.size(), 3u);
  const auto boxes = [](const Candidates& c) {
    std::vector<cv::Rect> out;
    for (const auto& ranked : c.ranked) out.push_back(c.Box(ranked.second));
    return out;
  };
  const cv::Rect dim(0, 0, 40, 30), bright(180, 80, 12, 12), middle(90, 40, 20, 20);
  const cv::Size image(200, 100);
  Candidates c = found;
  RankCandidates(options, nullptr, {}, image, &c);  // mass: the thesis, unchanged
  EXPECT_EQ(boxes(c), (std::vector<cv::Rect>{dim, middle, bright}));
  options.order = CandidateOrder::kPeak;
  c = found;
  RankCandidates(options, nullptr, {}, image, &c);
  EXPECT_EQ(boxes(c), (std::vector<cv::Rect>{bright, middle, dim}));
  EXPECT_FLOAT_EQ(static_cast<float>(c.ranked[0].first), 0.9f);
  // Attention at the dim block's corner: with proximity 0.1 (s = 22.4 px) the bright block,
  // 190 px away, falls to 0.9 x exp(-36) and the dim one comes first.
  options.proximity = 0.1f;
  const cv::Point2d focus(5, 5);
  c = found;
  RankCandidates(options, &focus, {}, image, &c);
  EXPECT_EQ(boxes(c), (std::vector<cv::Rect>{dim, middle, bright}));
  // Without a focus (the first target) proximity does nothing.
  c = found;
  RankCandidates(options, nullptr, {}, image, &c);
  EXPECT_EQ(boxes(c).front(), bright);
  // A face over the middle block's peak puts it first; a person's box does not.
  options.faces_first = true;
  c = found;
  RankCandidates(options, &focus, {{cv::Rect(85, 35, 30, 30), "face", 0.9f}}, image, &c);
  EXPECT_EQ(boxes(c), (std::vector<cv::Rect>{middle, dim, bright}));
  c = found;
  RankCandidates(options, &focus, {{cv::Rect(85, 35, 30, 30), "person", 0.9f}}, image, &c);
  EXPECT_EQ(boxes(c), (std::vector<cv::Rect>{dim, middle, bright}));
}

TEST(RegionsUnder, CountsEachCandidatesColourRegionsAndMarksTheCoveredOnes) {
  // Two colour regions, the left and the right half; one candidate across the middle.
  Segmentation segmentation;
  segmentation.labels = cv::Mat::zeros(10, 20, CV_32SC1);
  segmentation.labels(cv::Rect(10, 0, 10, 10)).setTo(1);
  segmentation.regions.resize(2);
  Candidates c;
  c.labels = cv::Mat(10, 20, CV_32SC1, cv::Scalar(-1));
  c.labels(cv::Rect(6, 2, 10, 5)).setTo(0);  // 4 x 5 on the left, 6 x 5 on the right
  c.sum = {1.0};
  c.ranked = {{1.0, 0}};
  cv::Mat covered = cv::Mat::zeros(10, 20, CV_8UC1);
  covered.at<uchar>(9, 19) = 255;
  const CandidateRegions under = RegionsUnder(c, segmentation, covered);
  ASSERT_EQ(under.overlaps.size(), 1u);
  EXPECT_EQ(under.overlaps[0], (std::map<int, int>{{0, 20}, {1, 30}}));
  EXPECT_EQ(under.taken, (std::vector<uint8_t>{0, 1}));
}

}  // namespace
}  // namespace attend
