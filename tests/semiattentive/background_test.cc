// The background of a frame and depth grouping (semiattentive/background.h) on a drawn street:
// the sky above the horizon (no measured disparity), the ground below it, and an upright
// object of two colour regions standing on the ground, with a box at another depth beside it.
#include "semiattentive/background.h"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>
#include <set>

namespace attend {
namespace {

constexpr int kWidth = 160, kHeight = 120;
enum Region { kSky, kRoad, kLeftHalf, kRightHalf, kNearBox, kRegions };

// The region adjacency of `labels` (4-neighbours), as the segmentation gives it.
RegionAdjacency AdjacencyOf(const cv::Mat& labels, int regions) {
  std::vector<std::set<int>> neighbours(regions);
  for (int y = 0; y < labels.rows; ++y) {
    for (int x = 0; x < labels.cols; ++x) {
      const int a = labels.at<int>(y, x);
      for (const cv::Point step : {cv::Point(1, 0), cv::Point(0, 1)}) {
        const cv::Point next(x + step.x, y + step.y);
        if (next.x >= labels.cols || next.y >= labels.rows) continue;
        const int b = labels.at<int>(next);
        if (a != b) neighbours[a].insert(b), neighbours[b].insert(a);
      }
    }
  }
  RegionAdjacency graph;
  graph.offsets.push_back(0);
  for (const std::set<int>& n : neighbours) {
    graph.neighbours.insert(graph.neighbours.end(), n.begin(), n.end());
    graph.offsets.push_back(static_cast<int>(graph.neighbours.size()));
  }
  return graph;
}

struct Street {
  Segmentation segmentation;
  cv::Mat disparity = cv::Mat::zeros(kHeight, kWidth, CV_32FC1);
  cv::Mat measured = cv::Mat::zeros(kHeight, kWidth, CV_8UC1);

  Street() {
    cv::Mat& labels = segmentation.labels;
    labels = cv::Mat(kHeight, kWidth, CV_32SC1, cv::Scalar(kRoad));
    labels(cv::Rect(0, 0, kWidth, 41)).setTo(kSky);
    labels(cv::Rect(60, 50, 15, 46)).setTo(kLeftHalf);
    labels(cv::Rect(75, 50, 15, 46)).setTo(kRightHalf);
    labels(cv::Rect(90, 50, 12, 20)).setTo(kNearBox);
    // A level camera: the ground's disparity 0.25 (v - 40) below the horizon at row 40.
    for (int y = 41; y < kHeight; ++y) disparity.row(y).setTo(0.25 * (y - 40));
    measured(cv::Rect(0, 41, kWidth, kHeight - 41)).setTo(255);
    disparity(cv::Rect(60, 50, 30, 46)).setTo(13.75f);  // the object, standing on row 95
    disparity(cv::Rect(90, 50, 12, 20)).setTo(20.f);     // a box nearer than the object
    segmentation.regions.resize(kRegions);
    for (int r = 0; r < kRegions; ++r) {
      segmentation.regions[r].area = cv::countNonZero(labels == r);
      segmentation.regions[r].bbox = cv::boundingRect(labels == r);
    }
    segmentation.adjacency = AdjacencyOf(labels, kRegions);
  }
};

TEST(Background, SkyRoadAndObjectAreToldApartOnAStereoFrame) {
  const Street street;
  SelectOptions options;
  SceneAnalysis scene(options);
  scene.Analyse(street.segmentation, street.disparity, street.measured);
  const SceneRegions& regions = scene.regions();
  ASSERT_TRUE(regions.ground.valid);
  EXPECT_EQ(regions.kind[kSky], BackgroundKind::kNoDepth);
  EXPECT_EQ(regions.kind[kRoad], BackgroundKind::kGround);
  EXPECT_EQ(regions.kind[kLeftHalf], BackgroundKind::kNone);
  EXPECT_EQ(regions.kind[kRightHalf], BackgroundKind::kNone);
  EXPECT_FLOAT_EQ(regions.disparity[kLeftHalf], 13.75f);
  EXPECT_TRUE(std::isnan(regions.disparity[kSky]));
  EXPECT_EQ(regions.mask.at<uint8_t>(10, 10), static_cast<uint8_t>(BackgroundKind::kNoDepth));
  EXPECT_EQ(regions.mask.at<uint8_t>(110, 10), static_cast<uint8_t>(BackgroundKind::kGround));
  EXPECT_EQ(regions.mask.at<uint8_t>(60, 70), 0);
  // A target on the object has none of its mask on background; one on the road all of it.
  cv::Mat mask = cv::Mat::zeros(kHeight, kWidth, CV_8UC1);
  mask(cv::Rect(60, 50, 30, 46)).setTo(255);
  EXPECT_EQ(scene.BackgroundShare(mask, cv::Rect(60, 50, 30, 46)), 0.0);
  mask.setTo(0);
  mask(cv::Rect(0, 100, 40, 20)).setTo(255);
  EXPECT_EQ(scene.BackgroundShare(mask, cv::Rect(0, 100, 40, 20)), 1.0);
}

// Heights and widths in metres need the baseline: the drawn ground's slope 0.25 px a row puts a
// camera of baseline 0.5 m at 2 m; a row y of the object is 2 - (y - 40) x 0.5 / 13.75 m above
// the ground, 1.64 m at its top (row 50), 0 at its base (row 95), 0.82 m on average: below
// max_height 2.5 m, above 0.5 m. A region 15 px wide at disparity 13.75 is 15 x 0.5 / 13.75 m.
TEST(Background, HeightsAndWidthsInMetresFollowFromTheBaseline) {
  const Street street;
  SelectOptions options;
  SceneAnalysis scene(options);
  EXPECT_TRUE(std::isnan(scene.WidthM(street.segmentation, kLeftHalf)));  // nothing analysed
  scene.set_baseline(0.5);
  scene.Analyse(street.segmentation, street.disparity, street.measured);
  EXPECT_EQ(scene.regions().kind[kLeftHalf], BackgroundKind::kNone);
  EXPECT_NEAR(scene.WidthM(street.segmentation, kLeftHalf), 15 * 0.5 / 13.75, 1e-6);
  EXPECT_TRUE(std::isnan(scene.WidthM(street.segmentation, kSky)));  // no depth
  options.max_height = 0.5f;
  SceneAnalysis low(options);
  low.set_baseline(0.5);
  low.Analyse(street.segmentation, street.disparity, street.measured);
  EXPECT_EQ(low.regions().kind[kLeftHalf], BackgroundKind::kHigh);
  // Without a baseline there is no height rule.
  SceneAnalysis unknown(options);
  unknown.Analyse(street.segmentation, street.disparity, street.measured);
  EXPECT_EQ(unknown.regions().kind[kLeftHalf], BackgroundKind::kNone);
}

TEST(Background, OnAMonocularFrameTheBorderRuleRemains) {
  const Street street;
  SelectOptions options;
  SceneAnalysis scene(options);
  scene.Analyse(street.segmentation, cv::Mat(), cv::Mat());
  const SceneRegions& regions = scene.regions();
  EXPECT_FALSE(regions.ground.valid);
  // The sky and the road each line much of the frame's edge.
  EXPECT_EQ(regions.kind[kSky], BackgroundKind::kBorder);
  EXPECT_EQ(regions.kind[kRoad], BackgroundKind::kBorder);
  EXPECT_EQ(regions.kind[kLeftHalf], BackgroundKind::kNone);
  // border_share 1 turns the rule off: the road (57 % of the image) is then background as a
  // large region only, and the sky (34 %) too, until max_area_fraction lets them be.
  options.border_share = 1.f;
  SceneAnalysis no_border(options);
  no_border.Analyse(street.segmentation, cv::Mat(), cv::Mat());
  EXPECT_EQ(no_border.regions().kind[kSky], BackgroundKind::kLarge);
  EXPECT_EQ(no_border.regions().kind[kRoad], BackgroundKind::kLarge);
  options.max_area_fraction = 0.6f;
  SceneAnalysis neither(options);
  neither.Analyse(street.segmentation, cv::Mat(), cv::Mat());
  EXPECT_EQ(neither.regions().kind[kSky], BackgroundKind::kNone);
  EXPECT_EQ(neither.regions().kind[kRoad], BackgroundKind::kNone);
}

TEST(Background, AnObjectSeedGrowsOverTheRegionsAtItsDepthAndNoFarther) {
  const Street street;
  SelectOptions options;
  SceneAnalysis scene(options);
  scene.Analyse(street.segmentation, street.disparity, street.measured);
  const std::vector<uint8_t> taken(kRegions, 0);
  std::vector<int> members = {kLeftHalf};
  double area = street.segmentation.regions[kLeftHalf].area;
  scene.GroupByDepth(street.segmentation, taken, 1e6, &members, &area);
  // The other half of the object joins; the nearer box, the road and the sky do not.
  EXPECT_EQ(members, (std::vector<int>{kLeftHalf, kRightHalf}));
  EXPECT_EQ(area, 2 * 15 * 46);
  // Off: nothing joins.
  options.group_depth = 0.f;
  SceneAnalysis off(options);
  off.Analyse(street.segmentation, street.disparity, street.measured);
  members = {kLeftHalf};
  off.GroupByDepth(street.segmentation, taken, 1e6, &members, &area);
  EXPECT_EQ(members, std::vector<int>{kLeftHalf});
}

}  // namespace
}  // namespace attend
