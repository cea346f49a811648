// The release rules (semiattentive/release.h): each rule on a target built to break it alone,
// the first rule that holds is the reason, and the duplicate rule's held pixels.
#include "semiattentive/release.h"

#include <gtest/gtest.h>

namespace attend {
namespace {

const cv::Rect kImage(0, 0, 100, 100);

ReleaseRules Rules() {
  SelectOptions select;
  select.min_area = 50;
  select.max_area_fraction = 0.2f;  // 2000 px
  DropOptions drop;
  drop.frames = 3;
  drop.max_shared = 0.5f;
  return ReleaseRules(select, drop);
}

TEST(ReleaseRules, ATargetWithinEveryBoundIsKept) {
  EXPECT_EQ(Rules().WhyReleased(cv::Rect(10, 10, 20, 20), 300, 2, 0.5, kImage),
            ReleaseReason::kNone);
}

TEST(ReleaseRules, EachRuleReleasesOnItsOwn) {
  const ReleaseRules rules = Rules();
  const cv::Rect box(10, 10, 20, 20);
  EXPECT_EQ(rules.WhyReleased(box, 2001, 0, 0.0, kImage), ReleaseReason::kTooLarge);
  EXPECT_EQ(rules.WhyReleased(cv::Rect(0, 0, 90, 90), 300, 0, 0.0, kImage),
            ReleaseReason::kSpansImage);
  EXPECT_EQ(rules.WhyReleased(cv::Rect(0, 0, 89, 100), 300, 0, 0.0, kImage),
            ReleaseReason::kNone);  // not 0.9 of the width
  EXPECT_EQ(rules.WhyReleased(cv::Rect(10, 10, 7, 7), 40, 0, 0.0, kImage),
            ReleaseReason::kTooSmall);
  EXPECT_EQ(rules.WhyReleased(box, 300, 3, 0.0, kImage), ReleaseReason::kLowSaliency);
  EXPECT_EQ(rules.WhyReleased(box, 300, 0, 0.51, kImage), ReleaseReason::kDuplicate);
}

TEST(ReleaseRules, TheFirstRuleThatHoldsIsTheReason) {
  // Too large, spanning the image, of low saliency and shared: too large comes first.
  EXPECT_EQ(Rules().WhyReleased(cv::Rect(0, 0, 100, 100), 9000, 5, 1.0, kImage),
            ReleaseReason::kTooLarge);
  // Too small and of low saliency: too small.
  EXPECT_EQ(Rules().WhyReleased(cv::Rect(0, 0, 5, 5), 25, 5, 0.0, kImage),
            ReleaseReason::kTooSmall);
}

TEST(ReleaseRules, LowSaliencyFramesCountInARowAndRestart) {
  const ReleaseRules rules = Rules();  // drop.min_saliency 0.1
  EXPECT_EQ(rules.LowFrames(0.05, 0), 1);
  EXPECT_EQ(rules.LowFrames(0.05, 2), 3);
  EXPECT_EQ(rules.LowFrames(0.2, 2), 0);
}

TEST(ReleaseRules, TheDuplicateRuleIsOffAtOne) {
  DropOptions drop;
  drop.max_shared = 1.f;
  EXPECT_FALSE(ReleaseRules(SelectOptions(), drop).duplicates());
  EXPECT_TRUE(Rules().duplicates());
}

TEST(HeldPixels, TheSharedShareIsTheHeldPartOfTheMask) {
  HeldPixels held;
  held.Reset(cv::Size(40, 40));
  cv::Mat older = cv::Mat::zeros(40, 40, CV_8UC1);
  older(cv::Rect(0, 0, 20, 40)).setTo(255);
  cv::Mat younger = cv::Mat::zeros(40, 40, CV_8UC1);
  younger(cv::Rect(10, 0, 20, 10)).setTo(255);  // 200 px, half on the older one
  EXPECT_DOUBLE_EQ(held.Shared(younger, 200), 0.0);
  held.Hold(older);
  EXPECT_DOUBLE_EQ(held.Shared(younger, 200), 0.5);
  held.Reset(cv::Size(40, 40));
  EXPECT_DOUBLE_EQ(held.Shared(younger, 200), 0.0);
}

}  // namespace
}  // namespace attend
