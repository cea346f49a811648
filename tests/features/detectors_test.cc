// The top-down channels (features/detectors.h): the gate, the `every` schedule and the map with
// a fake detector that finds painted squares, so every answer is known by construction; the
// model files' errors; OpenCV's HOG on real people when the MOT data is present.
#include "features/detectors.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "features/builtin.h"
#include "features/lazy_frame_context.h"
#include "io/ground_truth.h"
#include "tests/support/error_message.h"
#include "tests/support/temp_dir.h"
#include "util/error.h"

namespace attend {
namespace {

namespace fs = std::filesystem;
using testing::ConfigErrorOf;

// A fake detector with a 16x16 window whose object fills it: every white blob of at least 4
// px is an object, its box the blob's bounding box, its confidence the blob's grey level /
// 255. It records the size of each image it searches.
struct FakeDetector {
  std::vector<cv::Size> searched;

  static DetectorGeometry Geometry() { return {cv::Size(16, 16), 16.0}; }

  ObjectSearch Search() {
    return [this](const cv::Mat& image, double, std::vector<Detection>* found) {
      searched.push_back(image.size());
      found->clear();
      cv::Mat grey, mask, labels, stats, centroids;
      cv::cvtColor(image, grey, cv::COLOR_BGR2GRAY);
      cv::threshold(grey, mask, 40, 255, cv::THRESH_BINARY);
      const int count = cv::connectedComponentsWithStats(mask, labels, stats, centroids);
      for (int i = 1; i < count; ++i) {
        if (stats.at<int>(i, cv::CC_STAT_AREA) < 4) continue;
        const cv::Rect box(stats.at<int>(i, cv::CC_STAT_LEFT), stats.at<int>(i, cv::CC_STAT_TOP),
                           stats.at<int>(i, cv::CC_STAT_WIDTH),
                           stats.at<int>(i, cv::CC_STAT_HEIGHT));
        double peak = 0.0;
        cv::minMaxLoc(grey(box), nullptr, &peak);
        found->push_back({box, "marker", static_cast<float>(peak / 255.0)});
      }
    };
  }
};

// A black frame with grey squares (the markers) at `boxes`, each of level `levels[i]`.
cv::Mat Frame(cv::Size size, const std::vector<cv::Rect>& boxes,
              const std::vector<int>& levels = {}) {
  cv::Mat frame(size, CV_8UC3, cv::Scalar::all(0));
  for (size_t i = 0; i < boxes.size(); ++i) {
    frame(boxes[i]).setTo(cv::Scalar::all(i < levels.size() ? levels[i] : 255));
  }
  return frame;
}

ObjectChannelOptions Gated(double margin = 0.25, int min_height = 4) {
  ObjectChannelOptions options;
  options.gate = DetectorGate::kAttended;
  options.margin = margin;
  options.min_height = min_height;
  return options;
}

// Each side of `found` within `pixels` of `truth`'s.
void ExpectBoxNear(const cv::Rect& found, const cv::Rect& truth, int pixels) {
  EXPECT_NEAR(found.x, truth.x, pixels) << found << " vs " << truth;
  EXPECT_NEAR(found.y, truth.y, pixels) << found << " vs " << truth;
  EXPECT_NEAR(found.br().x, truth.br().x, pixels) << found << " vs " << truth;
  EXPECT_NEAR(found.br().y, truth.br().y, pixels) << found << " vs " << truth;
}

TEST(ObjectChannelOptions, DefaultsAreValid) {
  EXPECT_EQ(ObjectChannelOptions().Check(), "");
  EXPECT_EQ(HogPeopleOptions().Check(), "");
  FaceCascadeOptions faces;
  EXPECT_EQ(faces.Check(), "");
}

TEST(ObjectChannelOptions, CheckNamesTheField) {
  ObjectChannelOptions channel;
  channel.every = 0;
  EXPECT_NE(channel.Check().find("every"), std::string::npos);
  channel = ObjectChannelOptions();
  channel.max_height = channel.min_height - 1;
  EXPECT_NE(channel.Check().find("max_height"), std::string::npos);
  HogPeopleOptions hog;
  hog.stride = 12;
  EXPECT_NE(hog.Check().find("stride"), std::string::npos);
  hog = HogPeopleOptions();
  hog.model = "inria";
  EXPECT_NE(hog.Check().find("model"), std::string::npos);
  FaceCascadeOptions faces;
  faces.scale = 1.0;
  EXPECT_NE(faces.Check().find("scale"), std::string::npos);
}

TEST(ObjectChannel, GateFindsOnlyTheMarkersInsideTheRegionsAtTheirFramePlace) {
  const cv::Rect outside(40, 40, 20, 20), inside(200, 150, 20, 20);
  const cv::Mat frame = Frame({320, 240}, {outside, inside});
  FakeDetector fake;
  ObjectChannel channel(Gated(), FakeDetector::Geometry(), "marker", fake.Search());
  cv::Mat map;
  const cv::Rect region(195, 145, 30, 30);
  channel.Compute(frame, {region}, &map);
  ASSERT_EQ(channel.detections().size(), 1u);
  EXPECT_EQ(channel.detections()[0].label, "marker");
  // The crop (region grown by a quarter of its size on every side: 45x45 about its centre)
  // is scaled so that the smallest object it may hold, 30 / 1.5 = 20 px, fills the 16 px
  // window: by 0.8, to 36x36.
  ASSERT_EQ(fake.searched.size(), 1u);
  EXPECT_EQ(fake.searched[0], cv::Size(36, 36));
  ExpectBoxNear(channel.detections()[0].box, inside, 2);
  EXPECT_EQ(channel.last_searches(), 1);
}

TEST(ObjectChannel, SmallRegionsAreScaledUpAndMappedBack) {
  const cv::Rect marker(101, 57, 8, 8);
  const cv::Mat frame = Frame({320, 240}, {marker});
  FakeDetector fake;
  ObjectChannel channel(Gated(0.5, 4), FakeDetector::Geometry(), "marker", fake.Search());
  cv::Mat map;
  channel.Compute(frame, {cv::Rect(99, 55, 12, 12)}, &map);
  // Crop 24x24; the smallest object 12 / 2 = 6 px fills the window: scaled by 16 / 6.
  ASSERT_EQ(fake.searched.size(), 1u);
  EXPECT_EQ(fake.searched[0], cv::Size(64, 64));
  ASSERT_EQ(channel.detections().size(), 1u);
  ExpectBoxNear(channel.detections()[0].box, marker, 1);
}

TEST(ObjectChannel, OverlappingCropsDoNotDoubleADetection) {
  const cv::Rect marker(150, 100, 24, 24);
  const cv::Mat frame = Frame({320, 240}, {marker});
  FakeDetector fake;
  ObjectChannel channel(Gated(), FakeDetector::Geometry(), "marker", fake.Search());
  cv::Mat map;
  // A small region and a large one around the same marker: their crops (48x48 for objects of
  // 21.3 px and up, 225x180 for 80 px and up) cost 1296 and 1620 scaled pixels, their
  // bounding box searched for 21.3 px objects about 22800, so they are not merged.
  channel.Compute(frame, {cv::Rect(146, 96, 32, 32), cv::Rect(100, 60, 150, 120)}, &map);
  EXPECT_EQ(fake.searched.size(), 2u);  // both crops were searched
  ASSERT_EQ(channel.detections().size(), 1u);
  ExpectBoxNear(channel.detections()[0].box, marker, 2);
}

TEST(ObjectChannel, CropsThatOverlapMuchAreSearchedOnce) {
  const cv::Rect marker(150, 100, 24, 24);
  const cv::Mat frame = Frame({320, 240}, {marker});
  FakeDetector fake;
  ObjectChannel channel(Gated(), FakeDetector::Geometry(), "marker", fake.Search());
  cv::Mat map;
  // Crops (138, 88, 48, 48) for objects of 21.3 px and (130, 83, 60, 54) for 24 px: the
  // second holds the first, and searching it for 21.3 px objects (1828 scaled pixels) costs
  // less than both (1296 + 1440).
  channel.Compute(frame, {cv::Rect(146, 96, 32, 32), cv::Rect(140, 92, 40, 36)}, &map);
  ASSERT_EQ(fake.searched.size(), 1u);
  EXPECT_EQ(fake.searched[0].width, 45);  // 60 x 0.75
  EXPECT_NEAR(fake.searched[0].height, 40.5, 0.5);
  ASSERT_EQ(channel.detections().size(), 1u);
  ExpectBoxNear(channel.detections()[0].box, marker, 2);
}

TEST(MergeCrops, MergesWhereTheBoundingBoxCostsNoMoreThanBoth) {
  using Crops = std::vector<std::pair<cv::Rect, double>>;
  // Half overlapping, same smallest object: 60x40 = 2400 <= 1600 + 1600.
  EXPECT_EQ(MergeCrops({{{0, 0, 40, 40}, 16.0}, {{20, 0, 40, 40}, 16.0}}, 16.0),
            (Crops{{{0, 0, 60, 40}, 16.0}}));
  // Corners touching: 79x79 = 6241 > 3200.
  const Crops corners = {{{0, 0, 40, 40}, 16.0}, {{39, 39, 40, 40}, 16.0}};
  EXPECT_EQ(MergeCrops(corners, 16.0), corners);
  // Apart: never merged, however cheap.
  const Crops apart = {{{0, 0, 4, 4}, 16.0}, {{10, 0, 4, 4}, 16.0}};
  EXPECT_EQ(MergeCrops(apart, 16.0), apart);
  // A chain: the first two merge into (0, 0, 60, 40), which then takes the third.
  EXPECT_EQ(MergeCrops({{{0, 0, 40, 40}, 16.0}, {{20, 0, 40, 40}, 16.0}, {{50, 0, 30, 40}, 16.0}},
                       16.0),
            (Crops{{{0, 0, 80, 40}, 16.0}}));
  // The smaller smallest object costs the merge: (0, 0, 60, 40) for 8-px objects is
  // 2400 x 4 = 9600 > 1600 x 4 + 1600.
  const Crops scales = {{{0, 0, 40, 40}, 8.0}, {{20, 0, 40, 40}, 16.0}};
  EXPECT_EQ(MergeCrops(scales, 16.0), scales);
}

TEST(ObjectChannel, AttendedGateGlancesAtTheWholeFrameEveryScanEvery) {
  const cv::Rect looked_at(20, 20, 20, 20), elsewhere(100, 50, 20, 20);
  const cv::Mat frame = Frame({160, 120}, {looked_at, elsewhere});
  FakeDetector fake;
  ObjectChannelOptions options = Gated(0.25, 16);
  options.scan_every = 3;
  ObjectChannel channel(options, FakeDetector::Geometry(), "marker", fake.Search());
  cv::Mat map;
  for (int index = 0; index < 7; ++index) {
    fake.searched.clear();
    channel.Compute(frame, {cv::Rect(15, 15, 30, 30)}, &map);
    SCOPED_TRACE(::testing::Message() << "frame " << index);
    ASSERT_EQ(fake.searched.size(), 1u);
    if (index % 3 == 0) {
      // The whole frame at its own scale (16-px objects fill the 16-px window): both markers.
      EXPECT_EQ(fake.searched[0], cv::Size(160, 120));
      EXPECT_EQ(channel.detections().size(), 2u);
    } else {
      // Only the region's crop: the marker elsewhere is not found.
      EXPECT_NE(fake.searched[0], cv::Size(160, 120));
      ASSERT_EQ(channel.detections().size(), 1u);
      ExpectBoxNear(channel.detections()[0].box, looked_at, 2);
    }
  }
  // A new sequence glances at its first frame.
  channel.Restart();
  fake.searched.clear();
  channel.Compute(frame, {cv::Rect(15, 15, 30, 30)}, &map);
  ASSERT_EQ(fake.searched.size(), 1u);
  EXPECT_EQ(fake.searched[0], cv::Size(160, 120));
}

TEST(ObjectChannel, NoRegionsNoSearch) {
  FakeDetector fake;
  ObjectChannel channel(Gated(), FakeDetector::Geometry(), "marker", fake.Search());
  cv::Mat map;
  channel.Compute(Frame({320, 240}, {cv::Rect(10, 10, 20, 20)}), {}, &map);
  EXPECT_TRUE(fake.searched.empty());
  EXPECT_TRUE(channel.detections().empty());
  EXPECT_EQ(cv::countNonZero(map), 0);
}

TEST(ObjectChannel, AFrameOrACropSmallerThanTheWindowIsNotSearched) {
  FakeDetector fake;
  ObjectChannelOptions whole;
  whole.gate = DetectorGate::kFrame;
  whole.min_height = 16;  // scale 1: the 10x10 frame stays smaller than the window
  ObjectChannel frame_channel(whole, FakeDetector::Geometry(), "marker", fake.Search());
  cv::Mat map;
  frame_channel.Compute(Frame({10, 10}, {cv::Rect(2, 2, 5, 5)}), {}, &map);
  EXPECT_TRUE(fake.searched.empty());
  EXPECT_TRUE(frame_channel.detections().empty());
  EXPECT_EQ(map.size(), cv::Size(10, 10));

  // A region whose smallest object (min_height 40) needs the crop shrunk by 16 / 40: its
  // 12x12 crop becomes 5x5.
  ObjectChannel gated(Gated(0.1, 40), FakeDetector::Geometry(), "marker", fake.Search());
  gated.Compute(Frame({100, 100}, {cv::Rect(2, 2, 8, 8)}), {cv::Rect(0, 0, 10, 10)}, &map);
  EXPECT_TRUE(fake.searched.empty());
  EXPECT_TRUE(gated.detections().empty());
}

TEST(ObjectChannel, RegionsOutsideTheFrameAreIgnored) {
  FakeDetector fake;
  ObjectChannel channel(Gated(), FakeDetector::Geometry(), "marker", fake.Search());
  cv::Mat map;
  channel.Compute(Frame({100, 100}, {}), {cv::Rect(200, 200, 20, 20), cv::Rect()}, &map);
  EXPECT_TRUE(fake.searched.empty());
}

TEST(ObjectChannel, MapIsTheConfidenceInsideTheBoxesAndZeroOutside) {
  // Two markers of levels 153 and 204: confidences 0.6 and 0.8.
  const cv::Rect low(50, 50, 40, 40), right(120, 60, 30, 30);
  const cv::Mat apart = Frame({200, 150}, {low, right}, {153, 204});
  FakeDetector fake;
  ObjectChannelOptions whole;
  whole.gate = DetectorGate::kFrame;
  whole.min_height = 16;
  ObjectChannel channel(whole, FakeDetector::Geometry(), "marker", fake.Search());
  cv::Mat map;
  channel.Compute(apart, {}, &map);
  ASSERT_EQ(map.type(), CV_32FC1);
  ASSERT_EQ(map.size(), apart.size());
  ASSERT_EQ(channel.detections().size(), 2u);
  for (int y = 0; y < map.rows; ++y) {
    for (int x = 0; x < map.cols; ++x) {
      const float expected = low.contains({x, y}) ? 0.6f : right.contains({x, y}) ? 0.8f : 0.f;
      ASSERT_NEAR(map.at<float>(y, x), expected, 1e-6) << x << "," << y;
    }
  }
  // Overlapping boxes: the larger confidence.
  const cv::Rect high(80, 60, 30, 30);
  cv::Mat painted;
  DetectionPaint paint;
  PaintDetections({{low, "a", 0.6f}, {high, "a", 0.8f}}, paint, {200, 150}, &painted);
  EXPECT_FLOAT_EQ(painted.at<float>(55, 55), 0.6f);
  EXPECT_FLOAT_EQ(painted.at<float>(70, 85), 0.8f);   // in both
  EXPECT_FLOAT_EQ(painted.at<float>(85, 105), 0.8f);  // high only
  EXPECT_FLOAT_EQ(painted.at<float>(10, 10), 0.f);
  // Blurred: spread beyond the box, no higher than the largest confidence.
  paint.blur = 0.02;
  PaintDetections({{low, "a", 0.6f}}, paint, {200, 150}, &painted);
  double max = 0.0;
  cv::minMaxLoc(painted, nullptr, &max);
  EXPECT_LE(max, 0.6 + 1e-6);
  EXPECT_GT(painted.at<float>(70, low.x - 2), 0.f);
}

TEST(ObjectChannel, AGaussianShapePeaksAtTheBoxCentreWithItsSigma) {
  DetectionPaint paint;
  paint.shape = DetectionShape::kGaussian;
  paint.sigma = 0.25;
  // A 40x20 box at (20, 30): centre (39.5, 39.5) in pixel centres, sigma 10 by 5.
  const cv::Rect box(20, 30, 40, 20);
  cv::Mat painted;
  PaintDetections({{box, "face", 0.9f}}, paint, {100, 80}, &painted);
  double max = 0.0;
  cv::minMaxLoc(painted, nullptr, &max);
  // The pixels nearest the centre are half a pixel from it both ways.
  EXPECT_NEAR(max, 0.9 * std::exp(-0.5 * (0.25 / 100.0 + 0.25 / 25.0)), 1e-5);
  const auto at = [&painted](double x, double y) {
    return 0.9 * std::exp(-0.5 * ((x - 39.5) * (x - 39.5) / 100.0 + (y - 39.5) * (y - 39.5) / 25.0));
  };
  EXPECT_NEAR(painted.at<float>(39, 50), at(50, 39), 1e-5);
  EXPECT_NEAR(painted.at<float>(44, 39), at(39, 44), 1e-5);
  // 10.5 against 0.5 px from the centre along x: exp(-(10.5^2 - 0.5^2) / (2 x 100)).
  EXPECT_NEAR(painted.at<float>(39, 50) / painted.at<float>(39, 39), std::exp(-0.55), 1e-4);
  // Beyond 3 sigma: nothing; the corners of the box are far below the peak.
  EXPECT_EQ(painted.at<float>(39, 75), 0.f);
  EXPECT_LT(painted.at<float>(30, 20), 0.1f * 0.9f);
  // Two Gaussians: the maximum, not the sum.
  PaintDetections({{box, "face", 0.9f}, {box, "face", 0.5f}}, paint, {100, 80}, &painted);
  double both = 0.0;
  cv::minMaxLoc(painted, nullptr, &both);
  EXPECT_DOUBLE_EQ(both, max);
  // Centred at a quarter of the box's height: the peak moves up to y 34.5.
  paint.centre_y = 0.25;
  PaintDetections({{box, "person", 0.9f}}, paint, {100, 80}, &painted);
  cv::Point peak;
  cv::minMaxLoc(painted, nullptr, nullptr, nullptr, &peak);
  EXPECT_EQ(peak.x, 39);
  EXPECT_TRUE(peak.y == 34 || peak.y == 35) << peak;
  paint.centre_y = 0.5;
  // size_power -1: a box a quarter of the map's height paints 4 x its confidence, one an eighth
  // 8 x.
  paint.shape = DetectionShape::kBox;
  paint.size_power = -1.0;
  PaintDetections({{cv::Rect(0, 0, 10, 20), "face", 0.5f}, {cv::Rect(50, 50, 10, 10), "face", 0.5f}},
                  paint, {100, 80}, &painted);
  EXPECT_NEAR(painted.at<float>(5, 5), 2.0f, 1e-5);
  EXPECT_NEAR(painted.at<float>(55, 55), 4.0f, 1e-5);
}

TEST(ObjectChannel, FrameGateSearchesEveryNthFrameAndReusesTheDetections) {
  const cv::Rect first(20, 20, 20, 20), moved(60, 20, 20, 20);
  FakeDetector fake;
  ObjectChannelOptions whole;
  whole.gate = DetectorGate::kFrame;
  whole.min_height = 16;
  whole.every = 3;
  ObjectChannel channel(whole, FakeDetector::Geometry(), "marker", fake.Search());
  cv::Mat map;
  std::vector<int> searched_at;
  for (int frame = 0; frame < 7; ++frame) {
    channel.Compute(Frame({120, 80}, {frame < 2 ? first : moved}), {}, &map);
    if (channel.last_searches() > 0) searched_at.push_back(frame);
    ASSERT_EQ(channel.detections().size(), 1u) << frame;
    // Frames 1 and 2 reuse frame 0's detection (the marker moved at frame 2).
    ExpectBoxNear(channel.detections()[0].box, frame < 3 ? first : moved, 0);
    EXPECT_FLOAT_EQ(
        map.at<float>(channel.detections()[0].box.y + 1, channel.detections()[0].box.x + 1), 1.f);
  }
  EXPECT_EQ(searched_at, (std::vector<int>{0, 3, 6}));
  // A new sequence searches its first frame.
  channel.Restart();
  channel.Compute(Frame({120, 80}, {first}), {}, &map);
  EXPECT_EQ(channel.last_searches(), 1);
}

TEST(GateCrop, GrowsByTheMarginAndToTheWindowsAspectWithinTheFrame) {
  // 20x40 grown by 0.25 on each side: 30x60, already the 64x128 window's aspect.
  EXPECT_EQ(GateCrop({100, 100, 20, 40}, 0.25, {64, 128}, {320, 240}), cv::Rect(95, 90, 30, 60));
  // A narrow region is widened about its centre.
  EXPECT_EQ(GateCrop({100, 100, 10, 40}, 0.0, {64, 128}, {320, 240}), cv::Rect(95, 100, 20, 40));
  // Clipped to the frame.
  EXPECT_EQ(GateCrop({0, 0, 20, 40}, 0.25, {64, 128}, {320, 240}), cv::Rect(0, 0, 25, 50));
  // A wide, low region is not heightened: its height bounds the object's.
  EXPECT_EQ(GateCrop({50, 100, 200, 10}, 0.25, {64, 128}, {320, 240}), cv::Rect(0, 98, 300, 15));
}

TEST(ObjectChannel, ALowRegionOrARepeatedOneIsNotSearched) {
  FakeDetector fake;
  // A strip 10 px high: with min_height 20 its 15-px crop is below the 16-px window once
  // scaled by 16 / 20.
  ObjectChannel channel(Gated(0.25, 20), FakeDetector::Geometry(), "marker", fake.Search());
  cv::Mat map;
  const cv::Mat frame = Frame({320, 240}, {cv::Rect(60, 102, 100, 6)});
  channel.Compute(frame, {cv::Rect(50, 100, 200, 10)}, &map);
  EXPECT_TRUE(fake.searched.empty());
  // The same region twice (a target and its object file's prediction): one search.
  const cv::Rect marker(150, 100, 24, 24);
  channel.Compute(Frame({320, 240}, {marker}),
                  {cv::Rect(146, 96, 32, 32), cv::Rect(146, 96, 32, 32)}, &map);
  EXPECT_EQ(fake.searched.size(), 1u);
  ASSERT_EQ(channel.detections().size(), 1u);
  ExpectBoxNear(channel.detections()[0].box, marker, 2);
}

TEST(SuppressOverlaps, KeepsTheMostConfidentOfOverlappingBoxesOfOneLabel) {
  std::vector<Detection> detections = {{{0, 0, 10, 10}, "person", 0.5f},
                                       {{1, 1, 10, 10}, "person", 0.9f},
                                       {{1, 1, 10, 10}, "face", 0.7f},
                                       {{50, 50, 10, 10}, "person", 0.6f}};
  SuppressOverlaps(0.5, &detections);
  ASSERT_EQ(detections.size(), 3u);
  EXPECT_FLOAT_EQ(detections[0].confidence, 0.9f);
  EXPECT_EQ(detections[1].label, "face");
  EXPECT_EQ(detections[2].box, cv::Rect(50, 50, 10, 10));
}

TEST(ScoreToConfidence, IsMonotoneInZeroToOne) {
  float previous = 0.f;
  for (double score = -20.0; score <= 40.0; score += 0.5) {
    const float confidence = ScoreToConfidence(score);
    EXPECT_GT(confidence, 0.f);
    EXPECT_LE(confidence, 1.f);
    EXPECT_GE(confidence, previous);
    previous = confidence;
  }
  EXPECT_FLOAT_EQ(ScoreToConfidence(0.0), 0.5f);
  EXPECT_GT(ScoreToConfidence(1.0), ScoreToConfidence(0.5));
}

// --- the real detectors

std::unique_ptr<FeatureMap> Create(const std::string& name, const std::string& yaml,
                                   const FeatureSetup& setup = {}) {
  const std::vector<FeatureSpec> specs =
      ReadFeatureList(ParamBlock::Parse(yaml, "test.yaml"), "features");
  EXPECT_EQ(specs.at(0).name, name);
  return BuiltinFeatures().Create(specs.at(0), setup);
}

TEST(HogPeopleSearch, ImagesSmallerThanTheWindowGiveNothing) {
  for (const char* model : {"default", "daimler"}) {
    HogPeopleOptions options;
    options.model = model;
    ObjectSearch search = MakeHogPeopleSearch(options);
    std::vector<Detection> found = {{{0, 0, 1, 1}, "x", 1.f}};
    search(cv::Mat(40, 30, CV_8UC3, cv::Scalar::all(128)), 0.0, &found);
    EXPECT_TRUE(found.empty()) << model;
  }
  // Through the plugin: a frame smaller than the window in frame mode, and a crop at a corner
  // in gated mode.
  std::unique_ptr<FeatureMap> whole =
      Create("people", "features: [{name: people, gate: frame, min_height: 200}]");
  std::unique_ptr<FeatureMap> gated = Create("people", "features: [{name: people}]");
  const cv::Mat tiny(20, 30, CV_8UC3, cv::Scalar::all(90));
  LazyFrameContext context;
  context.Reset(0, tiny);
  context.set_attention_regions({cv::Rect(0, 0, 4, 4), cv::Rect(25, 15, 10, 10)});
  cv::Mat map;
  whole->Compute(context, &map);
  EXPECT_TRUE(whole->detections().empty());
  EXPECT_EQ(map.size(), tiny.size());
  gated->Compute(context, &map);
  EXPECT_TRUE(gated->detections().empty());
  EXPECT_EQ(cv::countNonZero(map), 0);
}

TEST(DetectorFeatures, AreRegisteredWithTheirKeys) {
  const FeatureRegistry registry = BuiltinFeatures();
  ASSERT_NE(registry.Find("people"), nullptr);
  ASSERT_NE(registry.Find("faces"), nullptr);
  EXPECT_NE(ConfigErrorOf([] {
              Create("people", "features: [{name: people, gate: everywhere}]");
            }).find("gate"),
            std::string::npos);
  EXPECT_NE(ConfigErrorOf([] {
              Create("people", "features: [{name: people, stride: 12}]");
            }).find("features.0.stride"),
            std::string::npos);
  EXPECT_NE(ConfigErrorOf([] {
              Create("people", "features: [{name: people, min_height: 60, max_height: 50}]");
            }).find("max_height"),
            std::string::npos);
  EXPECT_NE(ConfigErrorOf([] {
              Create("people", "features: [{name: people, model: inria}]");
            }).find("features.0.model"),
            std::string::npos);
  EXPECT_NE(ConfigErrorOf([] {
              Create("people", "features: [{name: people, scan_every: -1}]");
            }).find("features.0.scan_every"),
            std::string::npos);
}

// The message names the key, the file and opencv-data.
void ExpectModelError(const std::string& message, const std::string& file) {
  EXPECT_NE(message.find("features.0.model"), std::string::npos) << message;
  EXPECT_NE(message.find(file), std::string::npos) << message;
  EXPECT_NE(message.find("opencv-data"), std::string::npos) << message;
}

TEST(FacesFeature, AMissingModelIsAConfigErrorNamingKeyFileAndPackage) {
  testing::TempDir dir;
  const std::string missing = (dir.path() / "no_such_cascade.xml").string();
  ExpectModelError(
      ConfigErrorOf([&] { Create("faces", "features: [{name: faces, model: " + missing + "}]"); }),
      missing);
  // A relative one is looked up in the current folder and the attend folder.
  FeatureSetup setup;
  setup.home = dir.path().string();
  const std::string message = ConfigErrorOf(
      [&] { Create("faces", "features: [{name: faces, model: cascades/face.xml}]", setup); });
  ExpectModelError(message, "cascades/face.xml");
  EXPECT_NE(message.find(dir.path().string()), std::string::npos) << message;
}

TEST(FacesFeature, AnUnreadableModelIsAConfigError) {
  testing::TempDir dir;
  const std::string folder = (dir.path() / "cascade.xml").string();
  fs::create_directories(folder);
  ExpectModelError(
      ConfigErrorOf([&] { Create("faces", "features: [{name: faces, model: " + folder + "}]"); }),
      folder);
  if (geteuid() != 0) {  // root reads any file
    const std::string locked = dir.Write("locked.xml", "<opencv_storage></opencv_storage>\n");
    fs::permissions(locked, fs::perms::none);
    ExpectModelError(
        ConfigErrorOf([&] { Create("faces", "features: [{name: faces, model: " + locked + "}]"); }),
        locked);
  }
}

TEST(FacesFeature, AFileThatIsNotACascadeIsAConfigError) {
  testing::TempDir dir;
  for (const std::string& text :
       {std::string("not a cascade at all\n"), std::string(""),
        std::string("%YAML:1.0\nmean: [0.5, 0.3]\n"),
        std::string("<?xml version=\"1.0\"?>\n<opencv_storage><x>1</x></opencv_storage>\n")}) {
    const std::string file = dir.Write("face.xml", text);
    ExpectModelError(
        ConfigErrorOf([&] { Create("faces", "features: [{name: faces, model: " + file + "}]"); }),
        file);
  }
}

TEST(FacesFeature, TheDefaultCascadeLoadsAndFindsNothingInAnEmptyImage) {
  if (!fs::exists(kDefaultFaceCascade)) {
    GTEST_SKIP() << kDefaultFaceCascade
                 << " is absent: install Debian's opencv-data (scripts/install_deps.sh)";
  }
  for (const char* gate : {"frame", "attended"}) {
    std::unique_ptr<FeatureMap> faces =
        Create("faces", std::string("features: [{name: faces, gate: ") + gate + "}]");
    const cv::Mat grey(240, 320, CV_8UC3, cv::Scalar::all(120));
    LazyFrameContext context;
    context.Reset(0, grey);
    context.set_attention_regions({cv::Rect(100, 100, 40, 40), cv::Rect(300, 0, 20, 10)});
    cv::Mat map;
    faces->Compute(context, &map);
    EXPECT_TRUE(faces->detections().empty());
    EXPECT_EQ(map.size(), grey.size());
    EXPECT_EQ(cv::countNonZero(map), 0);
  }
}

// HOG on real people: TUD-Campus frames at 320x240 against gt/objects.csv (boxes scaled from
// 640x480), IoU 0.5, in frame mode and gated by the previous frame's boxes.
class TudCampus : public ::testing::Test {
 protected:
  void SetUp() override {
    folder_ = testing::SharedData() + "/mot/TUD-Campus";
    if (!fs::exists(folder_ + "/gt/objects.csv")) {
      GTEST_SKIP() << folder_ << " is absent (the MOT reference data): nothing to measure";
    }
    for (const GtObject& object : ReadObjectsCsv(folder_ + "/gt/objects.csv")) {
      if (object.frame >= kFrames || object.box.empty()) continue;
      truth_[object.frame].push_back(cv::Rect(cvRound(object.box.x / 2), cvRound(object.box.y / 2),
                                              cvRound(object.box.width / 2),
                                              cvRound(object.box.height / 2)));
    }
  }

  // Matched truth boxes over frames 1..kFrames-1 (greedy, IoU >= 0.5), and the detections.
  std::pair<int, int> Score(FeatureMap* people, bool gated) {
    int matched = 0, detections = 0;
    LazyFrameContext context;
    cv::Mat map;
    for (int frame = 0; frame < kFrames; ++frame) {
      char name[32];
      std::snprintf(name, sizeof(name), "/left/%06d.jpg", frame);
      cv::Mat image;
      cv::resize(cv::imread(folder_ + name), image, cv::Size(320, 240), 0, 0, cv::INTER_AREA);
      context.Reset(frame, image);
      context.set_attention_regions(gated && frame > 0 ? truth_[frame - 1]
                                                       : std::vector<cv::Rect>());
      people->Compute(context, &map);
      if (frame == 0) continue;
      std::vector<char> taken(truth_[frame].size(), 0);
      for (const Detection& detection : people->detections()) {
        EXPECT_EQ(detection.label, "person");
        EXPECT_GT(detection.confidence, 0.f);
        EXPECT_LE(detection.confidence, 1.f);
        EXPECT_GE(map.at<float>(detection.box.y + detection.box.height / 2,
                                detection.box.x + detection.box.width / 2),
                  detection.confidence);
        ++detections;
        for (size_t t = 0; t < truth_[frame].size(); ++t) {
          const cv::Rect& box = truth_[frame][t];
          const double overlap = (box & detection.box).area();
          const double iou = overlap / (box.area() + detection.box.area() - overlap);
          if (!taken[t] && iou >= 0.5) {
            taken[t] = 1;
            ++matched;
            break;
          }
        }
      }
    }
    return {matched, detections};
  }

  int TruthBoxes() const {
    int count = 0;
    for (const auto& [frame, boxes] : truth_)
      count += frame > 0 ? static_cast<int>(boxes.size()) : 0;
    return count;
  }

  static constexpr int kFrames = 6;
  std::string folder_;
  std::map<int, std::vector<cv::Rect>> truth_;
};

TEST_F(TudCampus, HogFindsThePeopleInTheWholeFrame) {
  std::unique_ptr<FeatureMap> people = Create("people", "features: [{name: people, gate: frame}]");
  const auto [matched, detections] = Score(people.get(), false);
  // Measured: 12 of the 30 truth boxes of frames 1..5, with 18 detections (docs/PERFORMANCE.md
  // has the whole sequences).
  EXPECT_EQ(TruthBoxes(), 30);
  EXPECT_GE(matched, 9) << "of " << TruthBoxes() << " with " << detections << " detections";
  EXPECT_LE(detections, 27);
}

TEST_F(TudCampus, GatedHogFindsThePeopleWhereAttentionLooks) {
  std::unique_ptr<FeatureMap> people = Create("people", "features: [{name: people}]");
  const auto [matched, detections] = Score(people.get(), true);
  // Measured: 11 of the 30, with 12 detections: what the gate shows the detector is a person.
  EXPECT_GE(matched, 8) << "of " << TruthBoxes() << " with " << detections << " detections";
  EXPECT_LE(detections, 18);
}

}  // namespace
}  // namespace attend
