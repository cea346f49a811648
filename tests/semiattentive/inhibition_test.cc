// The inhibition of return (semiattentive/inhibition.h): a kept target's mask dilated by the
// margin within its box, an occluded target's box and search area, and the inhibited saliency.
#include "semiattentive/inhibition.h"

#include <gtest/gtest.h>

namespace attend {
namespace {

const cv::Rect kImage(0, 0, 60, 40);

TEST(Inhibition, AKeptTargetInhibitsItsMaskGrownByTheMarginAndCoversItsMask) {
  InhibitionOptions options;
  options.margin = 2;
  Inhibition inhibition(options);
  inhibition.Reset(kImage.size());
  cv::Mat own = cv::Mat::zeros(kImage.size(), CV_8UC1);
  const cv::Rect box(20, 10, 10, 8);
  own(box).setTo(255);
  inhibition.AddTarget(own, box, kImage);
  EXPECT_EQ(cv::countNonZero(inhibition.inhibition()), 14 * 12);
  EXPECT_EQ(cv::countNonZero(inhibition.covered()), 10 * 8);
  EXPECT_EQ(inhibition.inhibition().at<float>(8, 18), 1.f);  // the margin's corner
  EXPECT_EQ(inhibition.inhibition().at<float>(7, 18), 0.f);
}

TEST(Inhibition, AnOccludedTargetInhibitsItsBoxAndWhereItWasSearched) {
  InhibitionOptions options;
  Inhibition inhibition(options);
  inhibition.Reset(kImage.size());
  inhibition.AddOccluded(cv::Rect(10, 10, 5, 5), cv::Rect(5, 5, 15, 15), kImage);
  EXPECT_EQ(cv::countNonZero(inhibition.inhibition()), 15 * 15);
  EXPECT_EQ(cv::countNonZero(inhibition.covered()), 15 * 15);

  options.occluded_search = false;
  Inhibition box_only(options);
  box_only.Reset(kImage.size());
  box_only.AddOccluded(cv::Rect(10, 10, 5, 5), cv::Rect(5, 5, 15, 15), kImage);
  EXPECT_EQ(cv::countNonZero(box_only.inhibition()), 5 * 5);

  options.keep_occluded = false;
  Inhibition none(options);
  none.Reset(kImage.size());
  none.AddOccluded(cv::Rect(10, 10, 5, 5), cv::Rect(5, 5, 15, 15), kImage);
  EXPECT_EQ(cv::countNonZero(none.inhibition()), 0);
}

TEST(Inhibition, TheInhibitedSaliencyIsZeroWhereInhibitedAndUnchangedElsewhere) {
  Inhibition inhibition(InhibitionOptions{});
  inhibition.Reset(kImage.size());
  inhibition.AddOccluded(cv::Rect(0, 0, 10, 10), cv::Rect(), kImage);
  const cv::Mat saliency(kImage.size(), CV_32FC1, cv::Scalar(0.5f));
  EXPECT_EQ(inhibition.Apply(saliency, ObjectFiles(ObjectFileOptions{})), 100);
  EXPECT_EQ(inhibition.inhibited().at<float>(5, 5), 0.f);
  EXPECT_EQ(inhibition.inhibited().at<float>(20, 30), 0.5f);
  EXPECT_DOUBLE_EQ(cv::sum(inhibition.inhibited())[0], 0.5 * (kImage.area() - 100));
}

}  // namespace
}  // namespace attend
