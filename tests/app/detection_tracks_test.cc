// The detector-alone peer's linker (app/detection_tracks.h) on boxes whose tracks are known by
// construction: constant velocities, a crossing, gaps and overlaps at a known IoU.
#include "app/detection_tracks.h"

#include <gtest/gtest.h>

#include <map>
#include <vector>

namespace attend {
namespace {

// The id given to each detection of one frame, in the detections' order.
std::vector<int> Ids(const std::vector<LinkedBox>& linked) {
  std::vector<int> ids;
  for (const LinkedBox& box : linked) ids.push_back(box.id);
  return ids;
}

// Two boxes meeting head on at 15 px a frame, 40 x 80 at the same height: A from the left,
// B from the right, 3 px apart in frame 7 and past each other in frame 8.
cv::Rect CrossingA(int frame) { return {10 + 15 * frame, 50, 40, 80}; }
cv::Rect CrossingB(int frame) { return {223 - 15 * frame, 50, 40, 80}; }

// The ids of A and B in each of 16 frames of the crossing; B is listed first in odd frames.
std::vector<std::pair<int, int>> LinkCrossing(const DetectionLinkOptions& options) {
  DetectionLinker linker(options);
  std::vector<std::pair<int, int>> ids;
  for (int f = 0; f < 16; ++f) {
    if (f % 2 == 0) {
      const std::vector<int> frame = Ids(linker.Link({CrossingA(f), CrossingB(f)}));
      ids.emplace_back(frame[0], frame[1]);
    } else {
      const std::vector<int> frame = Ids(linker.Link({CrossingB(f), CrossingA(f)}));
      ids.emplace_back(frame[1], frame[0]);
    }
  }
  return ids;
}

TEST(DetectionLinkOptions, DefaultsAreValidAndRangesChecked) {
  EXPECT_EQ(DetectionLinkOptions().Check(), "");
  DetectionLinkOptions options;
  options.match_iou = 0.0;
  EXPECT_NE(options.Check().find("match_iou"), std::string::npos) << options.Check();
  options = DetectionLinkOptions();
  options.max_missed = -1;
  EXPECT_NE(options.Check().find("max_missed"), std::string::npos) << options.Check();
  options = DetectionLinkOptions();
  options.velocity_frames = -1;
  EXPECT_NE(options.Check().find("velocity_frames"), std::string::npos) << options.Check();
}

TEST(DetectionLinker, TwoBoxesAtConstantVelocityKeepTheirIds) {
  DetectionLinker linker({});
  for (int f = 0; f < 40; ++f) {
    const cv::Rect a(10 + 5 * f, 20, 30, 60), b(300 - 4 * f, 100, 30, 60);
    // The detections' order changes from frame to frame; the ids follow the boxes.
    const std::vector<LinkedBox> linked = f % 3 == 0 ? linker.Link({a, b}) : linker.Link({b, a});
    ASSERT_EQ(linked.size(), 2u);
    const LinkedBox& on_a = f % 3 == 0 ? linked[0] : linked[1];
    const LinkedBox& on_b = f % 3 == 0 ? linked[1] : linked[0];
    EXPECT_EQ(on_a.id, 1) << "frame " << f;
    EXPECT_EQ(on_b.id, 2) << "frame " << f;
    EXPECT_EQ(on_a.box, a);  // the detection's box, not a prediction
    EXPECT_EQ(on_a.started, f == 0);
    EXPECT_EQ(on_b.started, f == 0);
    EXPECT_EQ(on_a.detection, f % 3 == 0 ? 0 : 1);
  }
  EXPECT_EQ(linker.tracks_started(), 2);
  EXPECT_EQ(linker.live_tracks(), 2);
}

TEST(DetectionLinker, CrossingBoxesKeepTheirIdsThanksToTheVelocity) {
  const std::vector<std::pair<int, int>> ids = LinkCrossing({});
  for (int f = 0; f < 16; ++f) {
    EXPECT_EQ(ids[f], std::make_pair(1, 2)) << "frame " << f;
  }
  // Without the prediction each track takes the box nearest its last one: in frame 8, where
  // the boxes have passed each other, that is the other's (IoU 28/52 against 25/55).
  DetectionLinkOptions still;
  still.velocity_frames = 0;
  const std::vector<std::pair<int, int>> swapped = LinkCrossing(still);
  EXPECT_EQ(swapped[7], std::make_pair(1, 2));
  EXPECT_EQ(swapped[8], std::make_pair(2, 1));
}

// One box at 6 px a frame, 30 px wide, unseen for `gap` frames from frame 10: after a gap of
// 5 frames or more it is no longer where it was last seen (36 px on).
std::map<int, int> IdsAroundAGap(int gap, int max_missed) {
  DetectionLinkOptions options;
  options.max_missed = max_missed;
  DetectionLinker linker(options);
  std::map<int, int> ids;
  for (int f = 0; f < 10 + gap + 5; ++f) {
    const bool seen = f < 10 || f >= 10 + gap;
    const std::vector<LinkedBox> linked = linker.Link(
        seen ? std::vector<cv::Rect>{{20 + 6 * f, 40, 30, 60}} : std::vector<cv::Rect>{});
    if (seen) ids[f] = linked.at(0).id;
  }
  return ids;
}

TEST(DetectionLinker, ABoxMissingForAtMostMaxMissedFramesResumesItsId) {
  for (const int gap : {1, 5, 8}) {
    const std::map<int, int> ids = IdsAroundAGap(gap, 8);
    for (const auto& [frame, id] : ids) EXPECT_EQ(id, 1) << "gap " << gap << ", frame " << frame;
  }
}

TEST(DetectionLinker, ABoxMissingForMoreThanMaxMissedFramesGetsANewId) {
  for (const int gap : {9, 12}) {
    const std::map<int, int> ids = IdsAroundAGap(gap, 8);
    EXPECT_EQ(ids.at(9), 1);
    EXPECT_EQ(ids.at(10 + gap), 2) << "gap " << gap;
    EXPECT_EQ(ids.rbegin()->second, 2) << "gap " << gap;
  }
  // max_missed 0: one frame unseen ends the track.
  EXPECT_EQ(IdsAroundAGap(1, 0).at(11), 2);
  EXPECT_EQ(IdsAroundAGap(1, 1).at(11), 1);
}

TEST(DetectionLinker, PairsOnlyAtMatchIouOrMore) {
  // A still 40 x 40 box, then one 20 px to the right: IoU 800 / 2400 = 1/3.
  for (const auto& [match_iou, same] : {std::pair{0.3, true}, std::pair{1.0 / 3.0, true},
                                        std::pair{0.34, false}, std::pair{0.5, false}}) {
    DetectionLinkOptions options;
    options.match_iou = match_iou;
    DetectionLinker linker(options);
    linker.Link({{0, 0, 40, 40}});
    const std::vector<LinkedBox> next = linker.Link({{20, 0, 40, 40}});
    EXPECT_EQ(next.at(0).id, same ? 1 : 2) << "match_iou " << match_iou;
    EXPECT_EQ(next.at(0).started, !same) << "match_iou " << match_iou;
  }
}

TEST(DetectionLinker, PairsOneToOne) {
  // Two detections on one track: the better overlap continues it, the other starts a track.
  DetectionLinker linker({});
  linker.Link({{0, 0, 40, 80}});
  const std::vector<LinkedBox> next = linker.Link({{10, 0, 40, 80}, {2, 0, 40, 80}});
  EXPECT_EQ(Ids(next), (std::vector<int>{2, 1}));
  EXPECT_TRUE(next[0].started);
  EXPECT_FALSE(next[1].started);
  // A frame without detections links nothing; the tracks wait.
  EXPECT_TRUE(linker.Link({}).empty());
  EXPECT_EQ(linker.live_tracks(), 2);
}

}  // namespace
}  // namespace attend
