// Seeds (semiattentive/seeds.h) on a drawn segmentation: the region seed, the object seed grown
// over the salient area, the detection seed clipped to its box, and the rules that start nothing.
#include "semiattentive/seeds.h"

#include <gtest/gtest.h>

namespace attend {
namespace {

// Background (region 0) with three 10 x 10 regions in a row: 1 and 2 touch, 3 stands apart.
Segmentation Drawn() {
  Segmentation segmentation;
  segmentation.labels = cv::Mat::zeros(40, 60, CV_32SC1);
  segmentation.labels(cv::Rect(10, 10, 10, 10)).setTo(1);
  segmentation.labels(cv::Rect(20, 10, 10, 10)).setTo(2);
  segmentation.labels(cv::Rect(40, 10, 10, 10)).setTo(3);
  segmentation.regions.resize(4);
  segmentation.regions[0].area = 40 * 60 - 300;
  for (int r = 1; r <= 3; ++r) segmentation.regions[r].area = 100;
  return segmentation;
}

// One candidate: salient (0.8) over regions 1 and 2, its most salient pixel at (12, 12).
struct Scene {
  Segmentation segmentation = Drawn();
  cv::Mat inhibited = cv::Mat::zeros(40, 60, CV_32FC1);
  Candidates candidates;
  CandidateRegions under;
  std::vector<Detection> detections;
  std::vector<uint8_t> detection_used;
  std::vector<cv::Rect> followed;
  double max_area = 1000.0;

  Scene() {
    inhibited(cv::Rect(10, 10, 20, 10)).setTo(0.8f);
    inhibited.at<float>(12, 12) = 0.9f;
    candidates.sum = {0.8 * 200};
    candidates.area = {200};
    candidates.peak = {cv::Point(12, 12)};
    candidates.peak_value = {0.9f};
    candidates.ranked = {{160.0, 0}};
    under.overlaps = {{{0, 5}, {1, 101}, {2, 100}}};  // region 1 is the most overlapped
    under.taken.assign(4, 0);
  }
  SeedFrame Frame() const {
    return {segmentation, inhibited,      candidates, under,
            detections,   detection_used, followed,   max_area};
  }
};

TEST(SeedMaker, ARegionSeedIsTheColourRegionTheCandidateOverlapsMost) {
  Scene scene;
  SeedMaker maker{SelectOptions()};
  Seed seed;
  ASSERT_TRUE(maker.Make(scene.Frame(), 0, nullptr, &seed));
  EXPECT_EQ(seed.best, 1);
  EXPECT_EQ(seed.members, std::vector<int>{1});
  EXPECT_EQ(seed.area, 100.0);
  EXPECT_EQ(seed.detection, -1);
  EXPECT_TRUE(seed.mask.empty());
}

TEST(SeedMaker, ARegionATargetHoldsOrLargerThanTheBoundStartsNothing) {
  Scene scene;
  SeedMaker maker{SelectOptions()};
  Seed seed;
  scene.under.taken[1] = 1;
  EXPECT_FALSE(maker.Make(scene.Frame(), 0, nullptr, &seed));
  scene.under.taken[1] = 0;
  scene.max_area = 99.0;
  EXPECT_FALSE(maker.Make(scene.Frame(), 0, nullptr, &seed));
}

TEST(SeedMaker, AnObjectSeedTakesTheRegionsOfTheSalientAreaWithinTheAreaBound) {
  Scene scene;
  SelectOptions options;
  options.seed = SeedKind::kObject;
  SeedMaker maker(options);
  Seed seed;
  ASSERT_TRUE(maker.Make(scene.Frame(), 0, nullptr, &seed));
  EXPECT_EQ(seed.members, (std::vector<int>{1, 2}));  // not 3, which is not salient
  EXPECT_EQ(seed.area, 200.0);
  scene.max_area = 150.0;  // the object is larger: its region alone
  ASSERT_TRUE(maker.Make(scene.Frame(), 0, nullptr, &seed));
  EXPECT_EQ(seed.members, std::vector<int>{1});
  EXPECT_EQ(seed.area, 100.0);
}

TEST(SeedMaker, ADetectionSeedIsTheRegionsMostlyInItsBoxClippedToTheBox) {
  Scene scene;
  SelectOptions options;
  options.seed = SeedKind::kDetection;
  options.min_area = 50;
  SeedMaker maker(options);
  // Region 1 wholly, region 2 by 6 of its 10 columns (>= seed_share 0.5), region 0 barely.
  scene.detections = {{cv::Rect(9, 9, 17, 11), "person", 0.9f}};
  scene.detection_used = {0};
  Seed seed;
  ASSERT_TRUE(maker.Make(scene.Frame(), 0, nullptr, &seed));
  EXPECT_EQ(seed.detection, 0);
  EXPECT_EQ(seed.members, (std::vector<int>{1, 2}));
  EXPECT_EQ(seed.area, 160.0);
  EXPECT_EQ(cv::countNonZero(seed.mask), 160);
  EXPECT_EQ(seed.mask.at<uchar>(15, 25), 255);
  EXPECT_EQ(seed.mask.at<uchar>(15, 26), 0);  // region 2 outside the box
}

TEST(SeedMaker, ADetectionAttendedAlreadyOrUnderNoneStartsNothing) {
  Scene scene;
  SelectOptions options;
  options.seed = SeedKind::kDetection;
  options.min_area = 50;
  scene.detections = {{cv::Rect(9, 9, 17, 11), "person", 0.9f}};
  scene.detection_used = {1};  // a target is on it
  SeedMaker maker(options);
  Seed seed;
  EXPECT_FALSE(maker.Make(scene.Frame(), 0, nullptr, &seed));
  scene.detection_used = {0};
  scene.followed = {cv::Rect(9, 9, 10, 11)};  // a followed target covers most of it
  EXPECT_FALSE(maker.Make(scene.Frame(), 0, nullptr, &seed));
  scene.followed.clear();
  scene.detections[0].box = cv::Rect(40, 0, 10, 10);  // not under the candidate's peak
  options.detected_only = true;
  SeedMaker detected_only(options);
  EXPECT_FALSE(detected_only.Make(scene.Frame(), 0, nullptr, &seed));
  options.detected_only = false;
  SeedMaker or_object(options);  // elsewhere an object seed
  ASSERT_TRUE(or_object.Make(scene.Frame(), 0, nullptr, &seed));
  EXPECT_EQ(seed.members, (std::vector<int>{1, 2}));
}

TEST(SeedMaker, TheMaskOfSeveralRegionsIsTheirPixels) {
  const Segmentation segmentation = Drawn();
  SeedMaker maker{SelectOptions()};
  const cv::Mat& mask = maker.MaskOf(segmentation, {1, 3});
  EXPECT_EQ(cv::countNonZero(mask), 200);
  EXPECT_EQ(mask.at<uchar>(15, 45), 255);
  EXPECT_EQ(mask.at<uchar>(15, 25), 0);
}

}  // namespace
}  // namespace attend
