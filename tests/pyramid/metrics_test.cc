#include "pyramid/metrics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "pyramid/segmentation.h"
#include "tests/support/error_message.h"

namespace attend {
namespace {

// Builds a CV_32SC1 label image from rows of labels.
cv::Mat Labels(std::initializer_list<std::initializer_list<int>> rows) {
  cv::Mat labels(static_cast<int>(rows.size()), static_cast<int>(rows.begin()->size()), CV_32SC1);
  int r = 0;
  for (const auto& row : rows) {
    int c = 0;
    for (int value : row) labels.at<int32_t>(r, c++) = value;
    ++r;
  }
  return labels;
}

// Two regions of 4 pixels each in a 4x2 image (left and right halves), both non-uniform.
TEST(SegmentationQuality, TwoEqualAreasByHand) {
  cv::Mat image(2, 4, CV_8UC3);
  // Region 0: BGR (0,0,0) twice and (0,0,2) twice; mean (0,0,1), each pixel 1 away: e0^2 = 4.
  image.at<cv::Vec3b>(0, 0) = {0, 0, 0};
  image.at<cv::Vec3b>(1, 0) = {0, 0, 0};
  image.at<cv::Vec3b>(0, 1) = {0, 0, 2};
  image.at<cv::Vec3b>(1, 1) = {0, 0, 2};
  // Region 1: (10,10,10) three times and (10,10,14); mean (10,10,11); squared distances
  // 1, 1, 1, 9: e1^2 = 12.
  image.at<cv::Vec3b>(0, 2) = {10, 10, 10};
  image.at<cv::Vec3b>(1, 2) = {10, 10, 10};
  image.at<cv::Vec3b>(0, 3) = {10, 10, 10};
  image.at<cv::Vec3b>(1, 3) = {10, 10, 14};
  const cv::Mat labels = Labels({{0, 0, 1, 1}, {0, 0, 1, 1}});

  const SegmentationQuality quality = EvaluateSegmentation(image, labels);
  EXPECT_EQ(quality.regions, 2);
  // F = sqrt(2) / (1000 * 8) * (4 / sqrt(4) + 12 / sqrt(4)) = sqrt(2) / 1000.
  EXPECT_NEAR(quality.f, std::sqrt(2.0) / 1000.0, 1e-15);
  // Both areas are 4, so R(4) = 2:
  // Q = sqrt(2) / (10000 * 8) * (4 / (1 + ln 4) + (2/4)^2 + 12 / (1 + ln 4) + (2/4)^2)
  //   = sqrt(2) / 80000 * (16 / 2.3862944 + 0.5) = 1.2736684e-4.
  const double q = std::sqrt(2.0) / 80000.0 * (16.0 / (1.0 + std::log(4.0)) + 0.5);
  EXPECT_NEAR(quality.q, q, 1e-15);
  EXPECT_NEAR(quality.q, 1.2736684e-4, 1e-11);
}

// The 2x2 image {a, b; c, d} with regions {a, b}, {c}, {d}: areas 2, 1, 1.
cv::Mat TwoByTwo() {
  cv::Mat image(2, 2, CV_8UC3);
  // Region 0: BGR (0,0,0) and (0,6,0); mean (0,3,0), each pixel 3 away: e0^2 = 18.
  image.at<cv::Vec3b>(0, 0) = {0, 0, 0};
  image.at<cv::Vec3b>(0, 1) = {0, 6, 0};
  image.at<cv::Vec3b>(1, 0) = {50, 60, 70};  // region 1, one pixel: e1^2 = 0
  image.at<cv::Vec3b>(1, 1) = {200, 0, 9};   // region 2, one pixel: e2^2 = 0
  return image;
}

TEST(SegmentationQuality, ThreeRegionsWithSharedAreaByHand) {
  const SegmentationQuality quality = EvaluateSegmentation(TwoByTwo(), Labels({{0, 0}, {1, 2}}));
  EXPECT_EQ(quality.regions, 3);
  // F = sqrt(3) / (1000 * 4) * 18 / sqrt(2) = 9 sqrt(6) / 4000 = 5.5113519e-3.
  EXPECT_NEAR(quality.f, 9.0 * std::sqrt(6.0) / 4000.0, 1e-15);
  // R(2) = 1, R(1) = 2; natural log, 1 + ln 1 = 1:
  // Q = sqrt(3) / (10000 * 4) * (18 / (1 + ln 2) + (1/2)^2 + (2/1)^2 + (2/1)^2)
  //   = sqrt(3) / 40000 * (10.631090 + 8.25) = 8.1757518e-4.
  const double q = std::sqrt(3.0) / 40000.0 * (18.0 / (1.0 + std::log(2.0)) + 8.25);
  EXPECT_NEAR(quality.q, q, 1e-15);
  EXPECT_NEAR(quality.q, 8.1757518e-4, 1e-11);
}

TEST(SegmentationQuality, UnlabelledPixelsAreLeftOutOfAreaAndErrors) {
  // The 2x2 case with a third column of unlabelled, wildly coloured pixels: N M counts only
  // labelled pixels, so F and Q are those of the 2x2 case.
  cv::Mat image(2, 3, CV_8UC3, cv::Scalar(255, 0, 255));
  TwoByTwo().copyTo(image(cv::Rect(0, 0, 2, 2)));
  image.at<cv::Vec3b>(1, 2) = {0, 255, 0};
  const SegmentationQuality with_unlabelled =
      EvaluateSegmentation(image, Labels({{0, 0, -1}, {1, 2, -1}}));
  const SegmentationQuality plain = EvaluateSegmentation(TwoByTwo(), Labels({{0, 0}, {1, 2}}));
  EXPECT_EQ(with_unlabelled.regions, 3);
  EXPECT_DOUBLE_EQ(with_unlabelled.f, plain.f);
  EXPECT_DOUBLE_EQ(with_unlabelled.q, plain.q);
}

TEST(SegmentationQuality, LabelsNeedNotBeContiguous) {
  // Labels 3, 7 and 9 are the same partition as 0, 1 and 2.
  const SegmentationQuality sparse = EvaluateSegmentation(TwoByTwo(), Labels({{7, 7}, {3, 9}}));
  const SegmentationQuality dense = EvaluateSegmentation(TwoByTwo(), Labels({{0, 0}, {1, 2}}));
  EXPECT_EQ(sparse.regions, 3);
  EXPECT_DOUBLE_EQ(sparse.f, dense.f);
  EXPECT_DOUBLE_EQ(sparse.q, dense.q);
}

// A 10x6 image of three constant colours: columns 0-4 (area 30), 5-7 (area 18), 8-9 (area 12).
cv::Mat ThreeBands(cv::Mat* labels) {
  cv::Mat image(6, 10, CV_8UC3);
  *labels = cv::Mat(6, 10, CV_32SC1);
  image.colRange(0, 5).setTo(cv::Scalar(10, 200, 30));
  image.colRange(5, 8).setTo(cv::Scalar(250, 20, 90));
  image.colRange(8, 10).setTo(cv::Scalar(0, 0, 255));
  labels->colRange(0, 5).setTo(0);
  labels->colRange(5, 8).setTo(1);
  labels->colRange(8, 10).setTo(2);
  return image;
}

TEST(SegmentationQuality, PerfectSegmentationLeavesOnlyTheAreaTerm) {
  cv::Mat labels;
  const cv::Mat image = ThreeBands(&labels);
  const SegmentationQuality quality = EvaluateSegmentation(image, labels);
  EXPECT_EQ(quality.regions, 3);
  EXPECT_EQ(quality.f, 0.0);  // no colour error at all
  // Q = sqrt(3) / (10000 * 60) * ((1/30)^2 + (1/18)^2 + (1/12)^2).
  const double q = std::sqrt(3.0) / 600000.0 * (1.0 / 900.0 + 1.0 / 324.0 + 1.0 / 144.0);
  EXPECT_NEAR(quality.q, q, 1e-18);
}

TEST(SegmentationQuality, OverSegmentingConstantColourKeepsFZeroAndRaisesQ) {
  cv::Mat labels;
  const cv::Mat image = ThreeBands(&labels);
  const SegmentationQuality perfect = EvaluateSegmentation(image, labels);
  // Split the 30-pixel band into two bands of 15: still constant colour per region.
  cv::Mat split = labels.clone();
  split(cv::Rect(0, 0, 5, 3)).setTo(3);
  const SegmentationQuality over = EvaluateSegmentation(image, split);
  EXPECT_EQ(over.regions, 4);
  EXPECT_EQ(over.f, 0.0);
  // Q = sqrt(4) / 600000 * ((2/15)^2 + (2/15)^2 + (1/18)^2 + (1/12)^2), the two 15-pixel
  // regions sharing their area: larger than the perfect segmentation's here (not always: see
  // SplittingCanLowerQWhenItBreaksUpEqualAreas).
  const double q = 2.0 / 600000.0 * (8.0 / 225.0 + 1.0 / 324.0 + 1.0 / 144.0);
  EXPECT_NEAR(over.q, q, 1e-18);
  EXPECT_GT(over.q, perfect.q);
}

TEST(SegmentationQuality, SplittingCanLowerQWhenItBreaksUpEqualAreas) {
  // A flat 300x1 image: every segmentation has zero colour error, Q is its area term alone.
  const cv::Mat image(1, 300, CV_8UC3, cv::Scalar(9, 99, 199));
  cv::Mat thirds(1, 300, CV_32SC1);
  thirds.colRange(0, 100).setTo(0);
  thirds.colRange(100, 200).setTo(1);
  thirds.colRange(200, 300).setTo(2);
  cv::Mat split = thirds.clone();
  split.colRange(200, 249).setTo(3);
  // Thirds: sqrt(3) / (10000 * 300) * 3 (3/100)^2 = 1.5588457e-9.
  // Split: sqrt(4) / (10000 * 300) * (2 (2/100)^2 + (1/49)^2 + (1/51)^2) = 1.0673071e-9.
  const SegmentationQuality three = EvaluateSegmentation(image, thirds);
  const SegmentationQuality four = EvaluateSegmentation(image, split);
  EXPECT_EQ(three.f, 0.0);
  EXPECT_EQ(four.f, 0.0);
  EXPECT_NEAR(three.q, 1.5588457e-9, 1e-16);
  EXPECT_NEAR(four.q, 1.0673071e-9, 1e-16);
  EXPECT_LT(four.q, three.q);
}

TEST(SegmentationQuality, UnderSegmentationHasColourError) {
  cv::Mat labels;
  const cv::Mat image = ThreeBands(&labels);
  const SegmentationQuality perfect = EvaluateSegmentation(image, labels);
  // Merging the 18- and 12-pixel bands: one region of two colours.
  cv::Mat merged = labels.clone();
  merged.colRange(8, 10).setTo(1);
  const SegmentationQuality under = EvaluateSegmentation(image, merged);
  EXPECT_EQ(under.regions, 2);
  EXPECT_GT(under.f, 0.0);
  // e^2 of the merged region: 18 and 12 pixels at squared distance |a - b|^2 (12/30)^2 and
  // |a - b|^2 (18/30)^2 from the mean, that is |a - b|^2 * 18 * 12 / 30.
  const double ab2 = 250.0 * 250.0 + 20.0 * 20.0 + 165.0 * 165.0;
  const double e2 = ab2 * 18.0 * 12.0 / 30.0;
  EXPECT_NEAR(under.f, std::sqrt(2.0) / 60000.0 * e2 / std::sqrt(30.0), 1e-12);
  EXPECT_GT(under.q, perfect.q);
}

TEST(SegmentationQuality, LargeFlatRegionHasExactlyZeroError) {
  // A sum-of-squares formula without shifting would cancel catastrophically here.
  const cv::Mat image(1500, 2000, CV_8UC3, cv::Scalar(251, 253, 255));
  const cv::Mat labels = cv::Mat::zeros(image.size(), CV_32SC1);
  const SegmentationQuality quality = EvaluateSegmentation(image, labels);
  EXPECT_EQ(quality.f, 0.0);
  // One region of area 3e6: Q = 1 / (10000 * 3e6) * (1 / 3e6)^2.
  EXPECT_NEAR(quality.q / (1.0 / (1e4 * 3e6) / 9e12), 1.0, 1e-12);
}

TEST(SegmentationQuality, NothingLabelledIsAnInputError) {
  const cv::Mat image(4, 4, CV_8UC3, cv::Scalar(1, 2, 3));
  const cv::Mat labels(4, 4, CV_32SC1, cv::Scalar(-1));
  const std::string message = testing::InputErrorOf([&] { EvaluateSegmentation(image, labels); });
  EXPECT_NE(message.find("no pixel"), std::string::npos) << message;
}

void LabelAllZero(const cv::Mat& bgr, cv::Mat* labels) {
  *labels = cv::Mat::zeros(bgr.size(), CV_32SC1);
}

TEST(ShiftVariance, OneRegionOnAFlatImageIsZero) {
  const cv::Mat image(60, 60, CV_8UC3, cv::Scalar(30, 140, 220));
  EXPECT_EQ(ShiftVariance(image, LabelAllZero, 40, 10), 0.0);
}

TEST(ShiftVariance, OneRegionOnARampIsTheMeanShiftOfTheMean) {
  // B = G = R = x: the mean of the window shifted by dx is dx more in each channel, so
  // RMSD_j = sqrt(3) dx, and over the 8 shifts of (0..2)^2 \ (0, 0):
  // SV = sqrt(3) * (3 * (0 + 1 + 2)) / 8 = 9 sqrt(3) / 8.
  cv::Mat image(12, 14, CV_8UC3);
  for (int x = 0; x < image.cols; ++x) image.col(x).setTo(cv::Scalar(x, x, x));
  EXPECT_NEAR(ShiftVariance(image, LabelAllZero, 8, 2), 9.0 * std::sqrt(3.0) / 8.0, 1e-12);
}

TEST(ShiftVariance, OneRegionPerPixelIsShiftInvariant) {
  cv::Mat image(40, 40, CV_8UC3);
  cv::randu(image, 0, 256);
  int calls = 0;
  const SegmentFunction every_pixel = [&calls](const cv::Mat& bgr, cv::Mat* labels) {
    EXPECT_EQ(bgr.size(), cv::Size(20, 20));
    ++calls;
    *labels = cv::Mat(bgr.size(), CV_32SC1);
    for (int i = 0; i < static_cast<int>(labels->total()); ++i) labels->at<int32_t>(i) = i;
  };
  // Each pixel is its own region and its own mean: every difference is 0.
  EXPECT_EQ(ShiftVariance(image, every_pixel, 20, 5), 0.0);
  EXPECT_EQ(calls, 36);  // the unshifted window and the 35 shifts
}

TEST(ShiftVariance, BipOnATexturedImageIsPositive) {
  // 4x4 blocks of random colour: the pyramid's regular grid meets the blocks differently from
  // one shift to the next, so the region means differ somewhere.
  std::mt19937 random(3);
  std::uniform_int_distribution<int> value(0, 255);
  cv::Mat image(72, 72, CV_8UC3);
  for (int y = 0; y < image.rows; y += 4) {
    for (int x = 0; x < image.cols; x += 4) {
      image(cv::Rect(x, y, 4, 4)).setTo(cv::Scalar(value(random), value(random), value(random)));
    }
  }
  Segmenter segmenter;
  Segmentation segmentation;
  const SegmentFunction bip = [&](const cv::Mat& bgr, cv::Mat* labels) {
    segmenter.Segment(bgr, &segmentation);
    *labels = segmentation.labels;
  };
  EXPECT_GT(ShiftVariance(image, bip, 60, 10), 0.0);
}

TEST(ShiftVariance, TooSmallImageIsAnInputErrorNamingTheSizeNeeded) {
  const cv::Mat image(30, 20, CV_8UC3, cv::Scalar(0, 0, 0));
  const std::string message =
      testing::InputErrorOf([&] { ShiftVariance(image, LabelAllZero, 16, 5); });
  EXPECT_NE(message.find("at least 21x21"), std::string::npos) << message;
  EXPECT_NE(message.find("20x30"), std::string::npos) << message;
}

}  // namespace
}  // namespace attend
