// attend track-detections end to end (app/track_detections.h; docs/ATTENTION.md, "The
// detector-alone peer"): its errors and exit statuses (SPEC 3.2), and, with the reference data
// (a YOLOX-nano model and a MOTChallenge sequence beside the project; skipped without them), a
// run that attend eval scores.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "io/frame_record.h"
#include "tests/cli/attend_cli.h"
#include "tests/support/attend_process.h"
#include "tests/support/sequence_maker.h"
#include "tests/support/temp_dir.h"

namespace fs = std::filesystem;

namespace attend {
namespace {

using testing::Attend;
using testing::Contains;
using testing::Result;
using testing::TempDir;

nlohmann::json ReadJson(const std::string& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

TEST(TrackDetectionsCli, AConfigurationWithoutTheChannelIsAConfigurationError) {
  TempDir dir;
  testing::MakeFolderSequence(dir.File("seq"), 2, 64, 48, false);
  dir.Write("colour.yaml", "features:\n  - {name: colour_contrast}\n");
  Result r = Attend(
      dir, {"track-detections", "--config", "colour.yaml", "--sequence", "seq", "--out", "run"});
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_TRUE(Contains(r.err, "colour.yaml: features: no feature named 'people'")) << r.err;
  EXPECT_FALSE(fs::exists(dir.File("run")));
  // --feature names another one: the same error for it.
  r = Attend(dir, {"track-detections", "--config", "colour.yaml", "--sequence", "seq", "--out",
                   "run", "--feature", "faces"});
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_TRUE(Contains(r.err, "no feature named 'faces'")) << r.err;
  // A bottom-up feature reports no detections.
  r = Attend(dir, {"track-detections", "--config", "colour.yaml", "--sequence", "seq", "--out",
                   "run", "--feature", "colour_contrast"});
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_TRUE(Contains(r.err, "reports no detections")) << r.err;
  EXPECT_FALSE(fs::exists(dir.File("run")));
}

TEST(TrackDetectionsCli, AMissingModelFileIsAConfigurationError) {
  TempDir dir;
  testing::MakeFolderSequence(dir.File("seq"), 2, 64, 48, false);
  dir.Write("dnn.yaml",
            "features:\n  - {name: people, backend: dnn, model: nowhere/yolox_nano.onnx}\n");
  const Result r = Attend(
      dir, {"track-detections", "--config", "dnn.yaml", "--sequence", "seq", "--out", "run"});
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_TRUE(Contains(r.err, "dnn.yaml:2")) << r.err;
  EXPECT_TRUE(Contains(r.err, "no such file: nowhere/yolox_nano.onnx")) << r.err;
  EXPECT_FALSE(fs::exists(dir.File("run")));
}

TEST(TrackDetectionsCli, UsageErrors) {
  TempDir dir;
  testing::MakeFolderSequence(dir.File("seq"), 2, 64, 48, false);
  dir.Write("hog.yaml", "features:\n  - {name: people}\n");
  // No source.
  Result r = Attend(dir, {"track-detections", "--config", "hog.yaml", "--out", "run"});
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_TRUE(Contains(r.err, "--sequence or --images")) << r.err;
  // Two sources.
  r = Attend(dir, {"track-detections", "--config", "hog.yaml", "--sequence", "seq", "--images",
                   "seq/left", "--out", "run"});
  EXPECT_EQ(r.status, 2) << r.err;
  // A match IoU out of range.
  r = Attend(dir, {"track-detections", "--config", "hog.yaml", "--sequence", "seq", "--out", "run",
                   "--match-iou", "1.5"});
  EXPECT_EQ(r.status, 2) << r.err;
  // A missing sequence is bad input.
  r = Attend(dir,
             {"track-detections", "--config", "hog.yaml", "--sequence", "nowhere", "--out", "run"});
  EXPECT_EQ(r.status, 3) << r.err;
  EXPECT_FALSE(fs::exists(dir.File("run")));
  // A run folder is not overwritten without --overwrite.
  r = Attend(dir, {"track-detections", "--config", "hog.yaml", "--sequence", "seq", "--out", "run",
                   "--quiet"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out, "");
  r = Attend(dir,
             {"track-detections", "--config", "hog.yaml", "--sequence", "seq", "--out", "run"});
  EXPECT_EQ(r.status, 2) << r.err;
  r = Attend(dir, {"track-detections", "--config", "hog.yaml", "--sequence", "seq", "--out", "run",
                   "--overwrite"});
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(Contains(r.out, "tracks of 'people' detections")) << r.out;
}

// YOLOX-nano on the first 10 frames of TUD-Campus (640 x 480, eight people walking), scored by
// attend eval against the sequence's ground truth.
TEST(TrackDetectionsCli, YoloxOnTudCampusIsScoredByEval) {
  const std::string model = testing::SharedData() + "/models/yolox/yolox_nano.onnx";
  const std::string sequence = testing::SharedData() + "/mot/TUD-Campus";
  if (!fs::exists(model) || !fs::exists(sequence + "/gt/objects.csv")) {
    GTEST_SKIP() << "no " << model << " or " << sequence << " (reference data)";
  }
  TempDir dir;
  dir.Write("yolox.yaml", "features:\n  - {name: people, backend: dnn, model: " + model +
                              ", gate: attended}\noutput:\n  dump: []\n");
  Result r = Attend(dir, {"track-detections", "--config", "yolox.yaml", "--sequence", sequence,
                          "--out", "run", "--frames", "0:9", "--quiet"});
  ASSERT_EQ(r.status, 0) << r.err;

  const std::vector<FrameRecord> records = ReadFrameRecords(dir.File("run/frames.jsonl"));
  ASSERT_EQ(records.size(), 10u);
  int beyond_working_width = 0;  // boxes reaching past x = 320, the working frame's width
  for (const FrameRecord& record : records) {
    EXPECT_FALSE(record.targets.empty()) << "frame " << record.frame;
    for (const TargetRecord& target : record.targets) {
      EXPECT_EQ(target.label, "person");
      EXPECT_LE(target.bbox.x + target.bbox.width, 640);
      beyond_working_width += target.bbox.x + target.bbox.width > 320;
    }
  }
  EXPECT_GT(beyond_working_width, 0);  // input pixels (SPEC 3.3)

  const nlohmann::json summary = ReadJson(dir.File("run/summary.json"));
  EXPECT_EQ(summary["frames"], 10);
  EXPECT_GT(summary["detectors"]["people"]["searched_pixels"].get<double>(), 0.0);
  EXPECT_GT(summary["detectors"]["people"]["ms"].get<double>(), 0.0);
  // The channel was made to search the whole frame every frame.
  EXPECT_TRUE(Contains(testing::ReadText(dir.File("run/config.yaml")), "gate: frame"));

  r = Attend(dir, {"eval", "run"});
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json mot = nlohmann::json::parse(r.out)["mot"]["iou_0.5"];
  EXPECT_EQ(mot["GT"].get<int>() > 0, true) << mot.dump();
  // The detector finds most of the people whole, and the linker keeps their ids over ten
  // frames.
  EXPECT_GE(mot["attended_whole_fraction"].get<double>(), 0.6) << mot.dump();
  EXPECT_GE(mot["IDF1"].get<double>(), 0.5) << mot.dump();
  EXPECT_LE(mot["ids_per_attended_object"].get<double>(), 1.5) << mot.dump();
}

}  // namespace
}  // namespace attend
