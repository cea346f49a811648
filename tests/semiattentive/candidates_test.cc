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
