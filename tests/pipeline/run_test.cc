#include "pipeline/run.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "pipeline/options_io.h"
#include "pipeline/run_folder.h"
#include "tests/support/sequence_maker.h"
#include "tests/support/temp_dir.h"
#include "util/error.h"

namespace fs = std::filesystem;

namespace attend {
namespace {

std::vector<nlohmann::json> ReadJsonLines(const std::string& path) {
  std::ifstream in(path);
  std::vector<nlohmann::json> lines;
  std::string line;
  while (std::getline(in, line)) lines.push_back(nlohmann::json::parse(line));
  return lines;
}

nlohmann::json ReadJson(const std::string& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

RunRequest TinyRequest(const testing::TempDir& dir, int frames) {
  RunRequest request;
  request.home = testing::ProjectRoot();
  request.options.sequence.source.folder = testing::MakeFolderSequence(dir.File("seq"), frames, 32, 24);
  request.options.sequence.resize = "native";
  request.out_dir = dir.File("run");
  return request;
}

TEST(RunSequence, WritesOneRecordPerFrameConfigAndSummary) {
  testing::TempDir dir;
  RunRequest request = TinyRequest(dir, 6);
  request.options.sequence.stride = 2;
  int progress_calls = 0;
  request.on_progress = [&](const RunProgress& p) {
    ++progress_calls;
    EXPECT_EQ(p.total, 3);
  };
  const RunSummary summary = RunSequence(request);
  EXPECT_EQ(summary.frames, 3);
  EXPECT_FALSE(summary.interrupted);
  EXPECT_EQ(progress_calls, 3);

  const std::vector<nlohmann::json> lines = ReadJsonLines(dir.File("run/frames.jsonl"));
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(lines[0]["frame"], 0);
  EXPECT_EQ(lines[1]["frame"], 2);
  EXPECT_EQ(lines[2]["frame"], 4);
  EXPECT_TRUE(lines[2]["targets"].is_array());
  EXPECT_TRUE(lines[2]["timings_ms"].contains("read"));

  const nlohmann::json json = ReadJson(dir.File("run/summary.json"));
  EXPECT_EQ(json["frames"], 3);
  EXPECT_EQ(json["interrupted"], false);
  EXPECT_TRUE(json["timings_ms"].contains("read"));
  EXPECT_EQ(json["sequence"]["size"][0], 32);
  EXPECT_EQ(json["tracker"], "bip");
  EXPECT_TRUE(fs::exists(dir.File("run/overlay/000004.png")));

  // config.yaml is a valid configuration that reproduces the options.
  const AttendOptions again = LoadOptions(dir.File("run/config.yaml"), {});
  EXPECT_EQ(again.sequence.stride, 2);
  EXPECT_EQ(OptionsToYaml(again), OptionsToYaml(request.options));
}

// summary.json names the tracker kind and config.yaml keeps it (the frames.jsonl targets' own
// "tracker" is checked in tests/semiattentive, on a scene that attends something).
TEST(RunSequence, TheRecordsNameTheTrackerKind) {
  testing::TempDir dir;
  RunRequest request = TinyRequest(dir, 4);
  request.options.attention.tracker.kind = TrackerKind::kKcf;
  RunSequence(request);
  EXPECT_EQ(ReadJson(dir.File("run/summary.json"))["tracker"], "kcf");
  EXPECT_EQ(LoadOptions(dir.File("run/config.yaml"), {}).attention.tracker.kind, TrackerKind::kKcf);
}

// One thread stops after the frame it is on; two finish the frame the second thread had
// already read as well (it was taken from the source), and take no further one.
TEST(RunSequence, StopFlagFinishesWithInterruptedSummary) {
  for (const int threads : {1, 2}) {
    testing::TempDir dir;
    RunRequest request = TinyRequest(dir, 6);
    request.options.threads = threads;
    std::atomic<bool> stop{false};
    request.stop = &stop;
    request.on_progress = [&](const RunProgress& p) {
      if (p.done == 2) stop = true;
    };
    const RunSummary summary = RunSequence(request);
    const int expected = threads == 1 ? 2 : 3;
    EXPECT_EQ(summary.frames, expected) << threads;
    EXPECT_TRUE(summary.interrupted);
    EXPECT_EQ(ReadJsonLines(dir.File("run/frames.jsonl")).size(), static_cast<size_t>(expected));
    EXPECT_EQ(ReadJson(dir.File("run/summary.json"))["interrupted"], true);
  }
}

TEST(RunSequence, CorruptFrameKeepsEarlierFramesAndNamesTheFrame) {
  testing::TempDir dir;
  RunRequest request = TinyRequest(dir, 6);
  testing::CorruptFrame(dir.File("seq"), "left", 3);
  try {
    RunSequence(request);
    FAIL() << "a corrupt frame must stop the run";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("frame 3"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("000003.png"), std::string::npos) << e.what();
  }
  EXPECT_EQ(ReadJsonLines(dir.File("run/frames.jsonl")).size(), 3u);
  const nlohmann::json summary = ReadJson(dir.File("run/summary.json"));
  EXPECT_EQ(summary["frames"], 3);
  EXPECT_EQ(summary["interrupted"], true);
  EXPECT_NE(summary["error"].get<std::string>().find("frame 3"), std::string::npos);
}

TEST(RunSequence, BadSourceFailsBeforeCreatingTheRunFolder) {
  testing::TempDir dir;
  RunRequest request;
  request.home = testing::ProjectRoot();
  request.options.sequence.source.folder = dir.File("missing");
  request.out_dir = dir.File("run");
  EXPECT_THROW(RunSequence(request), InputError);
  EXPECT_FALSE(fs::exists(dir.File("run")));
}

TEST(RunSequence, DisparityOnAMonocularSourceIsAConfigurationError) {
  testing::TempDir dir;
  RunRequest request;
  request.home = testing::ProjectRoot();
  request.options = ReadOptions(ParamBlock::Parse(
      "features:\n  - {name: colour_contrast}\n  - {name: disparity}\n", "c.yaml"));
  request.options.sequence.source.folder = testing::MakeFolderSequence(dir.File("mono"), 2, 48, 32, false);
  request.out_dir = dir.File("run");
  try {
    RunSequence(request);
    FAIL() << "disparity needs a stereo source";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("c.yaml:3: features.1.name: feature 'disparity' needs a "
                                         "stereo sequence"),
              std::string::npos)
        << e.what();
  }
  EXPECT_FALSE(fs::exists(dir.File("run")));
  // Disabled, it is fine.
  request.options.features[1].enabled = false;
  EXPECT_EQ(RunSequence(request).frames, 2);
}

TEST(RunSequence, UnknownFeatureIsAConfigurationErrorBeforeTheRunFolder) {
  testing::TempDir dir;
  RunRequest request;
  request.home = testing::ProjectRoot();
  request.options = ReadOptions(ParamBlock::Parse(
      "features:\n  - {name: colour_contrast}\n  - {name: disparty}\n", "c.yaml"));
  request.options.sequence.source.folder = testing::MakeFolderSequence(dir.File("mono"), 2, 16, 16, false);
  request.out_dir = dir.File("run");
  try {
    RunSequence(request);
    FAIL() << "an unknown feature must stop the run";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("c.yaml:3: features.1.name: unknown feature 'disparty'"),
              std::string::npos)
        << e.what();
  }
  EXPECT_FALSE(fs::exists(dir.File("run")));
}

TEST(RunFolder, RefusesNonEmptyFolderAndOverwriteKeepsForeignFiles) {
  testing::TempDir dir;
  dir.Write("run/notes.txt", "mine");
  dir.Write("run/summary.json", "{}");
  dir.Write("run/overlay/000000.png", "old");
  EXPECT_THROW(RunFolder(dir.File("run"), false), OutputError);
  { RunFolder folder(dir.File("run"), true); }
  EXPECT_TRUE(fs::exists(dir.File("run/notes.txt")));
  EXPECT_FALSE(fs::exists(dir.File("run/summary.json")));
  EXPECT_FALSE(fs::exists(dir.File("run/overlay")));
  EXPECT_TRUE(fs::exists(dir.File("run/frames.jsonl")));
  dir.Write("file", "x");
  EXPECT_THROW(RunFolder(dir.File("file"), true), OutputError);
  EXPECT_THROW(RunFolder("", true), OutputError);
}

// A frame whose second dump cannot be written leaves no NNNNNN.part.* of its first one (issue
// 30): the temporaries of a frame never recorded go when the folder is closed.
TEST(RunFolder, TheDumpsOfAFrameNeverRecordedLeaveNoTemporaries) {
  testing::TempDir dir;
  {
    RunFolder folder(dir.File("run"), false);
    FrameRecord first;
    first.frame = 0;
    folder.WriteImage("overlay", 0, cv::Mat(8, 8, CV_8UC3, cv::Scalar(1, 2, 3)));
    folder.AppendFrame(first);
    folder.WriteImage("overlay", 1, cv::Mat(8, 8, CV_8UC3, cv::Scalar(4, 5, 6)));
    EXPECT_TRUE(fs::exists(dir.File("run/overlay/000001.part.png")));
    // The saliency folder cannot be made: a file holds its name.
    dir.Write("run/saliency", "in the way");
    const cv::Mat map(8, 8, CV_32FC1, cv::Scalar(0.5f));
    EXPECT_THROW(folder.WriteMap("saliency", 1, map, map, true, false), OutputError);
  }
  EXPECT_TRUE(fs::exists(dir.File("run/overlay/000000.png")));
  EXPECT_FALSE(fs::exists(dir.File("run/overlay/000001.part.png")));
  EXPECT_FALSE(fs::exists(dir.File("run/overlay/000001.png")));
}

TEST(RunFolder, OverwriteRefusesAFolderThatIsNotARun) {
  // A folder of the user's that happens to have a `features/` subfolder is not a run: nothing
  // in it may be deleted.
  testing::TempDir dir;
  dir.Write("home/features/notes.txt", "precious");
  EXPECT_THROW(RunFolder(dir.File("home"), true), OutputError);
  EXPECT_TRUE(fs::exists(dir.File("home/features/notes.txt")));
}

TEST(DefaultRunFolder, NamesByTimeConfigAndSequenceAndIsUnique) {
  testing::TempDir dir;
  const std::string first = DefaultRunFolder(dir.path().string(), "configs/default.yaml", "lab");
  EXPECT_NE(first.find("-default-lab"), std::string::npos) << first;
  fs::create_directories(first);
  const std::string second = DefaultRunFolder(dir.path().string(), "configs/default.yaml", "lab");
  EXPECT_NE(first, second);
}

}  // namespace
}  // namespace attend
