#include "pyramid/segmentation.h"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>
#include <random>

namespace attend {
namespace {

Segmentation SegmentImage(const cv::Mat& bgr, SegmentationOptions options = {}) {
  Segmenter segmenter(options);
  Segmentation segmentation;
  segmenter.Segment(bgr, &segmentation);
  return segmentation;
}

SegmentationOptions Variant() {
  SegmentationOptions options;
  options.bip.link_across_kinds = true;
  return options;
}

// Every region lies within one colour of `image`: the segmentation never merges across an
// edge, whatever else it does.
void ExpectNoRegionCrossesAColourEdge(const cv::Mat& image, const Segmentation& s) {
  for (size_t r = 0; r < s.regions.size(); ++r) {
    const cv::Mat mask = s.labels == static_cast<int>(r);
    for (int c = 0; c < 3; ++c) {
      cv::Mat channel;
      cv::extractChannel(image, channel, c);
      double minimum, maximum;
      cv::minMaxLoc(channel, &minimum, &maximum, nullptr, nullptr, mask);
      EXPECT_EQ(minimum, maximum) << "region " << r << " crosses a colour edge";
    }
  }
}

// Number of 8-connected components of `mask`.
int Components(const cv::Mat& mask) {
  cv::Mat ignored;
  return cv::connectedComponents(mask, ignored, 8) - 1;
}

TEST(Segmentation, FlatImageIsOneRegion) {
  const Segmentation s = SegmentImage(cv::Mat(97, 131, CV_8UC3, cv::Scalar(200, 40, 90)));
  ASSERT_EQ(s.regions.size(), 1u);
  EXPECT_EQ(s.regions[0].area, 97 * 131);
  EXPECT_EQ(s.regions[0].perimeter, 0);
  EXPECT_TRUE(s.adjacency.boundaries.empty());
}

// Thesis figure 3.4a: four rectangles of different colours on a background.
cv::Mat FourRectangles(std::vector<cv::Rect>* boxes) {
  cv::Mat image(128, 128, CV_8UC3, cv::Scalar(180, 180, 180));
  *boxes = {cv::Rect(10, 12, 30, 20), cv::Rect(61, 9, 41, 33), cv::Rect(17, 70, 23, 45),
            cv::Rect(69, 77, 50, 31)};
  const cv::Scalar colours[] = {cv::Scalar(0, 0, 220), cv::Scalar(0, 200, 0), cv::Scalar(220, 0, 0),
                                cv::Scalar(0, 220, 220)};
  for (size_t i = 0; i < boxes->size(); ++i) {
    cv::rectangle(image, (*boxes)[i], colours[i], cv::FILLED);
  }
  return image;
}

void ExpectEachBoxIsOneRegion(const Segmentation& s, const std::vector<cv::Rect>& boxes) {
  for (const cv::Rect& box : boxes) {
    const int label = s.labels.at<int>(box.y + box.height / 2, box.x + box.width / 2);
    cv::Mat expected = cv::Mat::zeros(s.labels.size(), CV_8UC1);
    cv::rectangle(expected, box, 255, cv::FILLED);
    EXPECT_EQ(cv::countNonZero(expected != (s.labels == label)), 0) << "box " << box;
  }
}

TEST(Segmentation, FourRectanglesOnABackgroundAreFiveRegions) {
  std::vector<cv::Rect> boxes;
  const cv::Mat image = FourRectangles(&boxes);
  const Segmentation s = SegmentImage(image, Variant());
  EXPECT_EQ(s.regions.size(), 5u);
  ExpectEachBoxIsOneRegion(s, boxes);
}

TEST(Segmentation, FaithfulRulesKeepEachRectangleButMaySplitTheBackground) {
  // With the thesis's rules a regular and a virtual orphan never meet, so a background broken
  // around odd-placed rectangles stays in pieces; the rectangles are still exact.
  std::vector<cv::Rect> boxes;
  const cv::Mat image = FourRectangles(&boxes);
  SegmentationOptions options;
  options.min_region_area = 0;  // the pyramid's own roots
  const Segmentation s = SegmentImage(image, options);
  // Each rectangle exact, and the background in three pieces (docs/PYRAMID.md).
  EXPECT_EQ(s.regions.size(), 7u);
  ExpectEachBoxIsOneRegion(s, boxes);
  ExpectNoRegionCrossesAColourEdge(image, s);
}

// Thesis figure 3.4d: bars of aspect ratios from 1:2 to 1:40.
cv::Mat Bars(std::vector<cv::Rect>* bars) {
  cv::Mat image(160, 160, CV_8UC3, cv::Scalar(230, 230, 230));
  *bars = {cv::Rect(5, 5, 150, 4),   cv::Rect(7, 20, 3, 120),   cv::Rect(20, 30, 90, 9),
           cv::Rect(30, 60, 40, 20), cv::Rect(120, 40, 6, 110), cv::Rect(20, 150, 100, 5)};
  const cv::Scalar colours[] = {cv::Scalar(0, 0, 200),   cv::Scalar(0, 160, 0),
                                cv::Scalar(200, 0, 0),   cv::Scalar(0, 120, 200),
                                cv::Scalar(150, 0, 150), cv::Scalar(20, 20, 20)};
  for (size_t i = 0; i < bars->size(); ++i)
    cv::rectangle(image, (*bars)[i], colours[i], cv::FILLED);
  return image;
}

TEST(Segmentation, ElongatedBarsAreOneRegionEach) {
  std::vector<cv::Rect> bars;
  const cv::Mat image = Bars(&bars);
  for (const SegmentationOptions& options : {SegmentationOptions{}, Variant()}) {
    const Segmentation s = SegmentImage(image, options);
    ExpectEachBoxIsOneRegion(s, bars);
    ExpectNoRegionCrossesAColourEdge(image, s);
    if (options.bip.link_across_kinds) {
      EXPECT_EQ(s.regions.size(), bars.size() + 1);
    }
  }
}

TEST(Segmentation, EqualColoursThatDoNotTouchAreTwoRegions) {
  cv::Mat image(64, 96, CV_8UC3, cv::Scalar(240, 240, 240));
  cv::rectangle(image, cv::Rect(4, 10, 30, 30), cv::Scalar(0, 0, 255), cv::FILLED);
  cv::rectangle(image, cv::Rect(60, 20, 30, 30), cv::Scalar(0, 0, 255), cv::FILLED);
  for (const SegmentationOptions& options : {SegmentationOptions{}, Variant()}) {
    const Segmentation s = SegmentImage(image, options);
    EXPECT_NE(s.labels.at<int>(20, 20), s.labels.at<int>(30, 70));
    ExpectEachBoxIsOneRegion(s, {cv::Rect(4, 10, 30, 30), cv::Rect(60, 20, 30, 30)});
    if (options.bip.link_across_kinds) {
      EXPECT_EQ(s.regions.size(), 3u);
    }
  }
}

void ExpectAdjacencyMatchesLabels(const Segmentation& s);

// The labels run from 0 to the number of regions - 1.
void ExpectLabelsAreTheRegionIndices(const Segmentation& s) {
  double minimum, maximum;
  cv::minMaxLoc(s.labels, &minimum, &maximum);
  EXPECT_EQ(minimum, 0);
  EXPECT_EQ(maximum, static_cast<int>(s.regions.size()) - 1);
}

// Invariants that hold on any image.
class SegmentationInvariants : public ::testing::TestWithParam<int> {};

// Even seeds use the thesis's rules, odd ones the variant.

TEST_P(SegmentationInvariants, HoldOnRandomImages) {
  std::mt19937 random(GetParam());
  cv::Mat image(60 + GetParam() * 7, 80 + GetParam() * 5, CV_8UC3);
  cv::randu(image, 0, 256);
  // Blur some so that both the regular and the irregular parts are exercised.
  if (GetParam() % 4 < 2) cv::GaussianBlur(image, image, cv::Size(0, 0), 1.0 + GetParam());
  cv::Mat cylinder;
  BgrToCylinder(image, &cylinder);
  SegmentationOptions options;
  options.bip.link_across_kinds = GetParam() % 2 == 1;
  options.min_region_area = 0;  // the pyramid's own roots, to check them against the pixels
  Segmenter segmenter(options);
  Segmentation s;
  segmenter.SegmentCylinder(cylinder, &s);
  const int regions = static_cast<int>(s.regions.size());

  // Labels cover every pixel once, with indices 0..R-1.
  ExpectLabelsAreTheRegionIndices(s);
  long area_sum = 0;
  for (const RegionStats& r : s.regions) area_sum += r.area;
  EXPECT_EQ(area_sum, static_cast<long>(image.total()));

  // Each region is one 8-connected piece, and the root's mean is the mean over its pixels.
  std::vector<Bip::VertexRef> roots;
  segmenter.bip().LabelRoots(&s.labels, &roots);
  for (int r = 0; r < regions; ++r) {
    const cv::Mat mask = s.labels == r;
    EXPECT_EQ(Components(mask), 1) << "region " << r;
    const cv::Scalar mean = cv::mean(cylinder, mask);
    const float* root = segmenter.bip().level(roots[r].level).Feature(roots[r].id);
    EXPECT_NEAR(root[0], mean[0], 1e-2) << "region " << r;
    EXPECT_NEAR(root[1], mean[1], 1e-2) << "region " << r;
    EXPECT_NEAR(root[2], mean[2], 1e-2) << "region " << r;
    EXPECT_NEAR(s.regions[r].colour.v, mean[2], 1e-2);
  }

  ExpectAdjacencyMatchesLabels(s);
}

INSTANTIATE_TEST_SUITE_P(Seeds, SegmentationInvariants, ::testing::Range(0, 8));

// The graph's boundary lengths add up to the 4-neighbour pixel edges between regions, and each
// region's perimeter to the lengths of its edges.
void ExpectAdjacencyMatchesLabels(const Segmentation& s) {
  const int regions = static_cast<int>(s.regions.size());
  long boundary_edges = 0;
  std::vector<long> perimeter(regions, 0);
  for (int row = 0; row < s.labels.rows; ++row) {
    for (int col = 0; col < s.labels.cols; ++col) {
      const int a = s.labels.at<int>(row, col);
      if (col + 1 < s.labels.cols && s.labels.at<int>(row, col + 1) != a) ++boundary_edges;
      if (row + 1 < s.labels.rows && s.labels.at<int>(row + 1, col) != a) ++boundary_edges;
    }
  }
  long graph_total = 0;
  for (const RegionBoundary& boundary : s.adjacency.boundaries) {
    EXPECT_LT(boundary.a, boundary.b);
    graph_total += boundary.length;
    perimeter[boundary.a] += boundary.length;
    perimeter[boundary.b] += boundary.length;
    // Each end lists the other as its neighbour.
    EXPECT_NE(std::find(s.adjacency.NeighboursBegin(boundary.a),
                        s.adjacency.NeighboursEnd(boundary.a), boundary.b),
              s.adjacency.NeighboursEnd(boundary.a));
    EXPECT_NE(std::find(s.adjacency.NeighboursBegin(boundary.b),
                        s.adjacency.NeighboursEnd(boundary.b), boundary.a),
              s.adjacency.NeighboursEnd(boundary.b));
  }
  EXPECT_EQ(graph_total, boundary_edges);
  for (int r = 0; r < regions; ++r) EXPECT_EQ(perimeter[r], s.regions[r].perimeter);
}

// Grey texture: every pixel V = 128 + uniform noise in [-40, 40] (the same on all channels,
// so no hue), seeded. Its pixels spread by 80 / sqrt(12) = 23 about the mean.
cv::Mat GreyTexture(cv::Size size, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_int_distribution<int> noise(-40, 40);
  cv::Mat image(size, CV_8UC3);
  for (int row = 0; row < size.height; ++row) {
    for (int col = 0; col < size.width; ++col) {
      const uchar v = static_cast<uchar>(128 + noise(random));
      image.at<cv::Vec3b>(row, col) = cv::Vec3b(v, v, v);
    }
  }
  return image;
}

TEST(Segmentation, MergeBySpreadJoinsATextureAndKeepsFlatColoursApart) {
  // Left: the grey texture, which the colour threshold cuts into pieces. Right: a red and a
  // blue block, each flat (no spread), whose means are far from the texture's and from each
  // other. The merge joins the texture and leaves the blocks alone.
  cv::Mat image(96, 128, CV_8UC3);
  GreyTexture(cv::Size(64, 96), 7).copyTo(image(cv::Rect(0, 0, 64, 96)));
  image(cv::Rect(64, 0, 64, 48)).setTo(cv::Scalar(40, 40, 200));
  image(cv::Rect(64, 48, 64, 48)).setTo(cv::Scalar(200, 60, 40));
  SegmentationOptions thesis;
  const Segmentation cut = SegmentImage(image, thesis);
  // The thesis's regions: the texture in several pieces (so the merge has work to do).
  EXPECT_GT(cut.regions.size(), 4u);

  const cv::Rect texture(0, 0, 64, 96);
  const cv::Rect red(64, 0, 64, 48);
  const cv::Rect blue(64, 48, 64, 48);
  // Each block one region of exactly its pixels, and no region across the texture's edge.
  auto expect_blocks_whole = [&](const Segmentation& s) {
    for (const cv::Rect& block : {red, blue}) {
      const int label = s.labels.at<int>(block.y, block.x);
      EXPECT_EQ(s.regions[label].area, block.area());
      EXPECT_EQ(cv::countNonZero(s.labels(block) != label), 0);
    }
    for (size_t r = 0; r < s.regions.size(); ++r) {
      const cv::Mat inside = s.labels(texture) == static_cast<int>(r);
      const int count = cv::countNonZero(inside);
      EXPECT_TRUE(count == 0 || count == s.regions[r].area) << "region " << r;
    }
  };
  SegmentationOptions merged = thesis;
  merged.merge_spread = 1.f;
  const Segmentation s = SegmentImage(image, merged);
  expect_blocks_whole(s);
  ExpectAdjacencyMatchesLabels(s);
  // Within one spread, the texture becomes one region but for a few clumps of the noise whose
  // means lie beyond it (the seeded image leaves 4 of 20 to 49 pixels, each darker or lighter
  // than 128 by more than 23): at least 97 % of its pixels in one region.
  const RegionStats& main = s.regions[s.labels.at<int>(48, 32)];
  EXPECT_GE(main.area, 0.97 * texture.area());
  EXPECT_NEAR(main.colour.v, 128.f, 2.f);
  EXPECT_LT(s.regions.size(), cut.regions.size() / 5);
  EXPECT_EQ(Components(s.labels == s.labels.at<int>(48, 32)), 1);

  // Within two spreads, all of it.
  merged.merge_spread = 2.f;
  const Segmentation wide = SegmentImage(image, merged);
  ASSERT_EQ(wide.regions.size(), 3u);
  expect_blocks_whole(wide);
  EXPECT_EQ(wide.regions[wide.labels.at<int>(0, 0)].area, texture.area());
  ASSERT_EQ(wide.adjacency.boundaries.size(), 3u);

  // A factor too small to bridge the pieces' differences leaves most of them.
  merged.merge_spread = 0.05f;
  EXPECT_GT(SegmentImage(image, merged).regions.size(), cut.regions.size() / 2);
}

TEST(Segmentation, MergeBySpreadNeverJoinsTwoFlatColours) {
  // Four flat rectangles whose colours differ by one grey level: no spread, so no merge
  // whatever the factor (the thesis's threshold already joins them into one region at
  // T_max 40, so the threshold is set below their difference).
  cv::Mat image(64, 64, CV_8UC3);
  const int greys[4] = {100, 101, 102, 103};
  for (int i = 0; i < 4; ++i) {
    image(cv::Rect(32 * (i % 2), 32 * (i / 2), 32, 32)).setTo(cv::Scalar::all(greys[i]));
  }
  SegmentationOptions options;
  options.t_max = 0.5f;
  options.merge_spread = 100.f;
  EXPECT_EQ(SegmentImage(image, options).regions.size(), 4u);
}

// Invariants of the merge by spread on random images: every region one 8-connected piece of at
// least the minimum area, its statistics those of its pixels, and the graph that of the labels.
class MergeBySpreadInvariants : public ::testing::TestWithParam<int> {};

TEST_P(MergeBySpreadInvariants, HoldOnRandomImages) {
  cv::Mat image(70 + GetParam() * 9, 90 + GetParam() * 3, CV_8UC3);
  cv::theRNG().state = 1000 + GetParam();
  cv::randu(image, 0, 256);
  cv::GaussianBlur(image, image, cv::Size(0, 0), 0.8 + 0.2 * GetParam());
  cv::Mat cylinder;
  BgrToCylinder(image, &cylinder);
  SegmentationOptions options;
  options.t_max = 20.f;  // many regions before the merge, so that it has work to do
  options.merge_spread = 0.5f + 0.25f * GetParam();
  options.bip.link_across_kinds = GetParam() % 2 == 1;
  Segmenter segmenter(options);
  Segmentation s;
  segmenter.SegmentCylinder(cylinder, &s);
  const int regions = static_cast<int>(s.regions.size());
  ExpectLabelsAreTheRegionIndices(s);
  for (int r = 0; r < regions; ++r) {
    const cv::Mat mask = s.labels == r;
    EXPECT_EQ(Components(mask), 1) << "region " << r;
    EXPECT_EQ(s.regions[r].area, cv::countNonZero(mask)) << "region " << r;
    EXPECT_GE(s.regions[r].area, options.min_region_area) << "region " << r;
    EXPECT_EQ(s.regions[r].bbox, cv::boundingRect(mask)) << "region " << r;
    const cv::Scalar mean = cv::mean(cylinder, mask);
    EXPECT_NEAR(s.regions[r].colour.sx, mean[0], 1e-2) << "region " << r;
    EXPECT_NEAR(s.regions[r].colour.sy, mean[1], 1e-2) << "region " << r;
    EXPECT_NEAR(s.regions[r].colour.v, mean[2], 1e-2) << "region " << r;
  }
  ExpectAdjacencyMatchesLabels(s);
  // Regions are numbered by first appearance in raster order.
  int next = 0;
  for (int row = 0; row < s.labels.rows; ++row) {
    for (int col = 0; col < s.labels.cols; ++col) {
      const int label = s.labels.at<int>(row, col);
      EXPECT_LE(label, next);
      if (label == next) ++next;
    }
  }
  // Fewer regions than without the merge.
  options.merge_spread = 0.f;
  Segmenter thesis(options);
  Segmentation unmerged;
  thesis.SegmentCylinder(cylinder, &unmerged);
  EXPECT_LT(regions, static_cast<int>(unmerged.regions.size()));
}

INSTANTIATE_TEST_SUITE_P(Seeds, MergeBySpreadInvariants, ::testing::Range(0, 6));

TEST(Segmentation, MaskedSegmentationLeavesOutsidePixelsUnlabelled) {
  cv::Mat image(50, 50, CV_8UC3);
  cv::randu(image, 0, 256);
  cv::Mat mask = cv::Mat::zeros(50, 50, CV_8UC1);
  cv::circle(mask, cv::Point(25, 25), 15, 255, cv::FILLED);
  cv::Mat cylinder;
  BgrToCylinder(image, &cylinder);
  Segmenter segmenter;
  Segmentation s;
  segmenter.SegmentCylinder(cylinder, &s, mask);
  EXPECT_EQ(cv::countNonZero((s.labels < 0) != (mask == 0)), 0);
  long area_sum = 0;
  for (const RegionStats& r : s.regions) area_sum += r.area;
  EXPECT_EQ(area_sum, cv::countNonZero(mask));
}

TEST(Segmentation, RegionStatisticsOfATwoColourImage) {
  // Left half pure red, right half grey 100: saturation 255 vs 0, intensity 255 vs 100, and
  // one boundary of 40 pixel edges.
  cv::Mat image(40, 60, CV_8UC3, cv::Scalar(100, 100, 100));
  image(cv::Rect(0, 0, 30, 40)).setTo(cv::Scalar(0, 0, 255));
  const Segmentation s = SegmentImage(image);
  ASSERT_EQ(s.regions.size(), 2u);
  const RegionStats& red = s.regions[s.labels.at<int>(0, 0)];
  const RegionStats& grey = s.regions[s.labels.at<int>(0, 59)];
  EXPECT_NEAR(red.saturation, 255.f, 1e-3);
  EXPECT_NEAR(red.intensity, 255.f, 1e-3);
  EXPECT_NEAR(grey.saturation, 0.f, 1e-3);
  EXPECT_NEAR(grey.intensity, 100.f, 1e-3);
  EXPECT_EQ(red.perimeter, 40);
  EXPECT_EQ(red.bbox, cv::Rect(0, 0, 30, 40));
  ASSERT_EQ(s.adjacency.boundaries.size(), 1u);
  EXPECT_EQ(s.adjacency.boundaries[0].length, 40);
  EXPECT_EQ(s.adjacency.num_regions(), 2);
}

TEST(Segmentation, SmallRegionsMergeIntoTheirMostSimilarNeighbour) {
  // A 3x3 dark grey dot (V 80 below the background, beyond T_max) and a 4x4 dot of a very different
  // one, on a background beside a large red block: with a 20-pixel minimum both dots join the
  // background (their only neighbour), and nothing else changes.
  cv::Mat image(60, 80, CV_8UC3, cv::Scalar(200, 200, 200));
  image(cv::Rect(50, 0, 30, 60)).setTo(cv::Scalar(0, 0, 230));
  image(cv::Rect(10, 10, 3, 3)).setTo(cv::Scalar(120, 120, 120));
  image(cv::Rect(20, 30, 4, 4)).setTo(cv::Scalar(0, 150, 0));
  SegmentationOptions options = Variant();  // one background region, so counts are exact
  options.min_region_area = 0;
  EXPECT_EQ(SegmentImage(image, options).regions.size(), 4u);
  options.min_region_area = 20;
  const Segmentation s = SegmentImage(image, options);
  ASSERT_EQ(s.regions.size(), 2u);
  EXPECT_EQ(s.labels.at<int>(11, 11), s.labels.at<int>(0, 0));
  EXPECT_EQ(s.labels.at<int>(31, 21), s.labels.at<int>(0, 0));
  EXPECT_EQ(s.regions[s.labels.at<int>(0, 0)].area, 50 * 60);
  EXPECT_EQ(s.regions[s.labels.at<int>(0, 79)].area, 30 * 60);
  // The merged statistics are those of the pixels.
  cv::Mat cylinder;
  BgrToCylinder(image, &cylinder);
  const int background = s.labels.at<int>(0, 0);
  EXPECT_NEAR(s.regions[background].intensity, cv::mean(cylinder, s.labels == background)[2], 1e-3);
}

TEST(Segmentation, AfterMergingEveryRegionIsLargeEnoughAndConnected) {
  cv::Mat image(90, 120, CV_8UC3);
  cv::randu(image, 0, 256);
  cv::GaussianBlur(image, image, cv::Size(0, 0), 1.5);
  SegmentationOptions options;
  options.min_region_area = 25;
  const Segmentation s = SegmentImage(image, options);
  for (size_t r = 0; r < s.regions.size(); ++r) {
    EXPECT_GE(s.regions[r].area, 25) << "region " << r;
    EXPECT_EQ(Components(s.labels == static_cast<int>(r)), 1) << "region " << r;
  }
}

TEST(SegmentationOptions, DefaultsAreValidAndCheckNamesTheField) {
  EXPECT_EQ(SegmentationOptions().Check(), "");
  EXPECT_EQ(BipOptions().Check(), "");
  SegmentationOptions options;
  options.t_max = 0.f;
  EXPECT_NE(options.Check().find("t_max"), std::string::npos);
  options = SegmentationOptions();
  options.min_region_area = -1;
  EXPECT_NE(options.Check().find("min_region_area"), std::string::npos);
  options = SegmentationOptions();
  options.merge_spread = -1.f;
  EXPECT_NE(options.Check().find("merge_spread"), std::string::npos);
  options = SegmentationOptions();
  options.bip.max_levels = 0;
  EXPECT_NE(options.Check().find("max_levels"), std::string::npos);
}

TEST(Segmentation, TinyImagesAndEmptyMasks) {
  // Degenerate shapes: one pixel, one row, one column, 2x2; every pixel gets a label, and a
  // flat image is one region whatever its shape.
  for (const cv::Size size : {cv::Size(1, 1), cv::Size(7, 1), cv::Size(1, 7), cv::Size(2, 2),
                              cv::Size(3, 64), cv::Size(65, 3)}) {
    const Segmentation flat = SegmentImage(cv::Mat(size, CV_8UC3, cv::Scalar(10, 90, 200)));
    EXPECT_EQ(flat.regions.size(), 1u) << size;
    EXPECT_EQ(flat.regions[0].area, size.area()) << size;
    cv::Mat noise(size, CV_8UC3);
    cv::randu(noise, 0, 256);
    const Segmentation random = SegmentImage(noise);
    long area = 0;
    for (const RegionStats& r : random.regions) area += r.area;
    EXPECT_EQ(area, size.area()) << size;
    EXPECT_EQ(cv::countNonZero(random.labels < 0), 0) << size;
  }
  // A mask that takes every pixel out leaves no region and no label.
  cv::Mat image(20, 30, CV_8UC3, cv::Scalar(1, 2, 3)), cylinder;
  BgrToCylinder(image, &cylinder);
  Segmenter segmenter;
  Segmentation s;
  segmenter.SegmentCylinder(cylinder, &s, cv::Mat::zeros(20, 30, CV_8UC1));
  EXPECT_TRUE(s.regions.empty());
  EXPECT_EQ(cv::countNonZero(s.labels >= 0), 0);
  EXPECT_EQ(s.adjacency.num_regions(), 0);
}

}  // namespace
}  // namespace attend
