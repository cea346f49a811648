// attend track-detections' controller (app/track_detections.h): the configuration it runs with,
// the channels it refuses, and a run folder that attend eval scores. The HOG people channel
// needs no model file; the dnn backend on real frames is tested in
// tests/cli/track_detections_cli_test.cc.
#include "app/track_detections.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "app/evaluate_run.h"
#include "io/frame_record.h"
#include "io/ground_truth.h"
#include "tests/support/error_message.h"
#include "tests/support/sequence_maker.h"
#include "tests/support/temp_dir.h"
#include "util/error.h"

namespace attend {
namespace {

// A configuration with a bottom-up feature and the HOG people channel gated by attention.
constexpr const char* kConfig = R"(features:
  - {name: motion, weight: 1.0}
  - {name: people, weight: 2.0, gate: attended, every: 4, scan_every: 3}
output:
  dump: []
)";

DetectionTracksRequest TracksRequest(const testing::TempDir& dir) {
  DetectionTracksRequest request;
  request.run.config = dir.Write("peer.yaml", kConfig);
  request.run.source.folder = testing::MakeFolderSequence(dir.File("seq"), 4, 160, 120, false);
  request.run.out = dir.File("run");
  request.run.quiet = true;
  return request;
}

TEST(ResolveDetectorOptions, KeepsTheChannelAloneOnTheWholeFrameEveryFrame) {
  testing::TempDir dir;
  DetectionTracksRequest request = TracksRequest(dir);
  request.run.frames = "1:2";
  const AttendOptions options = ResolveDetectorOptions(request);
  ASSERT_EQ(options.features.size(), 1u);
  const FeatureSpec& people = options.features[0];
  EXPECT_EQ(people.name, "people");
  EXPECT_EQ(people.weight, 2.0);
  EXPECT_EQ(people.params.GetString("gate", ""), "frame");
  EXPECT_EQ(people.params.GetInt("every", 0), 1);
  // The source and range as attend run resolves them.
  EXPECT_EQ(options.sequence.first_frame, 1);
  EXPECT_EQ(options.sequence.last_frame, 2);
  EXPECT_TRUE(std::filesystem::path(options.sequence.source.folder).is_absolute());
}

TEST(ResolveDetectorOptions, RefusesAMissingDisabledOrBottomUpFeature) {
  testing::TempDir dir;
  DetectionTracksRequest request = TracksRequest(dir);
  const auto error = [&request] {
    return testing::ConfigErrorOf([&request] { ResolveDetectorOptions(request); });
  };
  request.feature = "faces";
  EXPECT_NE(error().find("peer.yaml: features: no feature named 'faces'"), std::string::npos)
      << error();
  request.feature = "motion";
  EXPECT_NE(error().find("the feature 'motion' reports no detections"), std::string::npos)
      << error();
  request.feature = "people";
  request.run.sets = {"features.people.enabled=false"};
  EXPECT_NE(error().find("the feature 'people' is disabled"), std::string::npos) << error();
  request.run.sets.clear();
  request.link.match_iou = 1.5;
  EXPECT_NE(error().find("match_iou"), std::string::npos) << error();
  request.link = DetectionLinkOptions();
  EXPECT_EQ(error(), "");
}

TEST(TrackDetections, WritesARunFolderThatEvalScores) {
  testing::TempDir dir;
  const DetectionTracksRequest request = TracksRequest(dir);
  const RunSummary summary = TrackDetections(request, ResolveDetectorOptions(request));
  EXPECT_EQ(summary.frames, 4);
  EXPECT_FALSE(summary.interrupted);
  // Uniform frames hold no person: a record a frame, without tracks.
  const std::vector<FrameRecord> records = ReadFrameRecords(dir.File("run/frames.jsonl"));
  ASSERT_EQ(records.size(), 4u);
  for (int f = 0; f < 4; ++f) {
    EXPECT_EQ(records[f].frame, f);
    EXPECT_TRUE(records[f].targets.empty());
    EXPECT_GT(records[f].timings.Get("feature.people"), 0.0);
  }
  std::ifstream in(dir.File("run/summary.json"));
  const nlohmann::json json = nlohmann::json::parse(in);
  EXPECT_EQ(json["frames"], 4);
  EXPECT_EQ(json["tracker"], "detections");
  EXPECT_EQ(json["pixels"]["records"], "input");
  EXPECT_GT(json["detectors"]["people"]["searched_pixels"].get<double>(), 0.0);
  EXPECT_EQ(json["linking"]["match_iou"], 0.3);
  EXPECT_EQ(json["linking"]["max_missed"], 30);
  EXPECT_FALSE(std::filesystem::exists(dir.File("run/overlay")));

  // attend eval on the folder: the ground truth of the sequence, nobody found.
  std::filesystem::create_directories(dir.File("seq/gt"));
  GtObject person;
  person.box = cv::Rect2d(40, 20, 30, 80);
  person.visible_fraction = 1.0;
  person.id = 1;
  std::vector<GtObject> truth;
  for (int f = 0; f < 4; ++f) {
    person.frame = f;
    truth.push_back(person);
  }
  WriteObjectsCsv(dir.File("seq/gt/objects.csv"), truth);
  const nlohmann::ordered_json report = EvaluateRunFolder(dir.File("run"), "");
  EXPECT_EQ(report["frames"], 4);
  EXPECT_EQ(report["mot"]["iou_0.5"]["GT"], 4);
  EXPECT_EQ(report["mot"]["iou_0.5"]["FN"], 4);
  EXPECT_EQ(report["mot"]["iou_0.5"]["targets_started"], 0);
}

}  // namespace
}  // namespace attend
