// The template search (tracker/template_search.h) on a frame whose answer is known: a red
// square moved by (5, 3) pixels over a flat grey background.
#include "tracker/template_search.h"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "tracker/tracker_mode.h"

namespace attend {
namespace tracker_internal {
namespace {

const cv::Rect kStart(40, 40, 16, 16);
const cv::Point kMoved(5, 3);

// The frame with the square moved, over-segmented whole, and a target whose level-0 template is
// the square where it started, its colour `colour` (BGR) as the pyramid sees it.
class TemplateSearchTest : public ::testing::Test {
 protected:
  void SetUp() override {
    cv::Mat frame(128, 128, CV_8UC3, cv::Scalar(128, 128, 128));
    frame(kStart + kMoved).setTo(cv::Scalar(40, 40, 210));
    const cv::Mat all(frame.size(), CV_8UC1, cv::Scalar(255));
    BuildHierarchy(frame, cv::Mat(), TrackSimilarity::kColour, all, {0, 0, 128, 128}, 0, 10.f, &h_);
    target_.box = kStart;
    target_.roi = {0, 0, 128, 128};
    const BipLevel& base = h_.bip->level(0);
    const float* red = base.Feature(h_.Cell(0, kStart.x + kMoved.x, kStart.y + kMoved.y));
    TemplateLevel t;
    t.cells = kStart;
    t.area.assign(kStart.area(), 1);
    t.weight.assign(kStart.area(), 1.f);
    for (int i = 0; i < kStart.area(); ++i) t.colour.insert(t.colour.end(), red, red + 3);
    target_.levels = {t};
  }
  void TearDown() override { h_.Release(); }

  Hierarchy h_{nullptr};  // a pool of its own
  Target target_;
  TemplateSearch search_;
};

TEST_F(TemplateSearchTest, ReturnsTheDisplacementWithTheBestOverlap) {
  SearchScoring scoring;
  const Match match = search_.SearchLevel(target_, h_, 0, nullptr, scoring);
  EXPECT_TRUE(match.found);
  EXPECT_EQ(match.level, 0);
  EXPECT_EQ(match.displacement, kMoved);
  EXPECT_DOUBLE_EQ(match.overlap, 1.0);
  EXPECT_FALSE(match.scored);  // no appearance
}

TEST_F(TemplateSearchTest, AWindowWithoutTheMatchFindsNothingAbove) {
  SearchScoring scoring;
  scoring.min_overlap = 0.9;
  const cv::Rect window(-2, -2, 5, 5);  // displacements -2..2: at best 13 x 15 of 16 x 16 cells
  const Match match = search_.SearchLevel(target_, h_, 0, &window, scoring);
  EXPECT_FALSE(match.found);
  EXPECT_EQ(match.level, -1);
  EXPECT_EQ(match.overlap, 0.0);
  scoring.min_overlap = 0.7;
  const Match partial = search_.SearchLevel(target_, h_, 0, &window, scoring);
  EXPECT_TRUE(partial.found);
  EXPECT_EQ(partial.displacement, cv::Point(2, 2));
  EXPECT_DOUBLE_EQ(partial.overlap, 13.0 / 16 * 15.0 / 16);  // 13 columns, 15 rows
}

TEST_F(TemplateSearchTest, ReturnsTheCorrelationOfTheAppearanceMatch) {
  // A correlation map that peaks where the square went, and is 0.2 everywhere else.
  CorrelationMap map;
  map.zncc.create(128 - kStart.height + 1, 128 - kStart.width + 1, CV_32FC1);
  map.zncc.setTo(0.2f);
  map.box_in_area = kStart.tl();
  map.zncc.at<float>(kStart.y + kMoved.y, kStart.x + kMoved.x) = 0.9f;
  SearchScoring scoring;
  scoring.appearance = &map;
  scoring.appearance_share = 0.7;
  scoring.min_score = 0.3;
  const Match match = search_.SearchLevel(target_, h_, 0, nullptr, scoring);
  EXPECT_TRUE(match.found);
  EXPECT_TRUE(match.scored);
  EXPECT_EQ(match.displacement, kMoved);
  EXPECT_NEAR(match.correlation, 0.9, 1e-6);
  // Above every score: not accepted, but the best displacement's correlation is still given.
  scoring.min_score = 0.99;
  const Match refused = search_.SearchLevel(target_, h_, 0, nullptr, scoring);
  EXPECT_FALSE(refused.found);
  EXPECT_TRUE(refused.scored);
  EXPECT_NEAR(refused.correlation, 0.9, 1e-6);
}

TEST(TrackerModes, ThePoliciesDifferWhereTheModesDo) {
  TrackerOptions options;
  const std::unique_ptr<ModePolicy> thesis = MakeThesisMode(options);
  const std::unique_ptr<ModePolicy> bounded = MakeBoundedMode(BoundedTrackerOptions());
  EXPECT_FALSE(thesis->BoxIsTarget());
  EXPECT_TRUE(bounded->BoxIsTarget());
  cv::Mat mask(50, 60, CV_8UC1, cv::Scalar(0));
  mask(cv::Rect(10, 20, 5, 4)).setTo(255);
  EXPECT_EQ(thesis->StartBounds(mask, mask.size()), cv::Rect(0, 0, 60, 50));
  EXPECT_EQ(bounded->StartBounds(mask, mask.size()), cv::Rect(10, 20, 5, 4));
  // Only the bounded mode with the appearance reads the frame in grey.
  const cv::Mat frame(50, 60, CV_8UC3, cv::Scalar(10, 20, 30));
  EXPECT_TRUE(thesis->Frame(frame, cv::Mat()).grey.empty());
  EXPECT_EQ(bounded->Frame(frame, cv::Mat()).grey.type(), CV_8UC1);
}

}  // namespace
}  // namespace tracker_internal
}  // namespace attend
