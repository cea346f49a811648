// RunObserver: a caller's observers hear every processed frame (after the dumps), and one that
// throws stops the run as a bad frame does, keeping the frames done.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "io/ground_truth.h"
#include "pipeline/frame_pipeline.h"
#include "io/frame_record.h"
#include "pipeline/run.h"
#include "tests/support/sequence_maker.h"
#include "tests/support/temp_dir.h"
#include "util/error.h"

namespace attend {
namespace {

namespace fs = std::filesystem;

RunRequest Request(const testing::TempDir& dir, int frames) {
  RunRequest request;
  request.home = testing::ProjectRoot();
  request.options.sequence.source.folder = testing::MakeFolderSequence(dir.File("seq"), frames, 32, 24);
  request.options.sequence.resize = "native";
  request.options.output.dump = {"overlay"};
  request.out_dir = dir.File("run");
  return request;
}

// Records what it hears; throws at frame `fail_at` (-1: never).
class Listener : public RunObserver {
 public:
  explicit Listener(int fail_at = -1) : fail_at_(fail_at) {}
  void OnFrame(const StereoFrame& frame, const FramePipeline& pipeline,
               const FrameRecord& record) override {
    if (frame.index == fail_at_) throw OutputError("listener: no room for frame 2");
    frames.push_back(frame.index);
    records.push_back(record.frame);
    saliency_sizes.push_back(pipeline.saliency().size());
  }
  std::vector<int> frames, records;
  std::vector<cv::Size> saliency_sizes;

 private:
  int fail_at_;
};

TEST(RunObserver, HearsEveryFrameAfterTheDumps) {
  testing::TempDir dir;
  RunRequest request = Request(dir, 4);
  Listener listener;
  request.observers = {&listener};
  const RunSummary summary = RunSequence(request);
  EXPECT_EQ(summary.frames, 4);
  EXPECT_EQ(listener.frames, (std::vector<int>{0, 1, 2, 3}));
  EXPECT_EQ(listener.records, listener.frames);
  for (const cv::Size& size : listener.saliency_sizes) EXPECT_EQ(size, cv::Size(32, 24));
  // The dumps are observers too: every frame's overlay is there.
  for (int frame = 0; frame < 4; ++frame) {
    EXPECT_TRUE(fs::exists(dir.File("run/overlay/" + FrameStem(frame) + ".png"))) << frame;
  }
}

TEST(RunObserver, OneThatThrowsStopsTheRunKeepingTheFramesDone) {
  testing::TempDir dir;
  RunRequest request = Request(dir, 4);
  Listener listener(2);
  request.observers = {&listener};
  EXPECT_THROW(RunSequence(request), OutputError);
  std::ifstream records(dir.File("run/frames.jsonl"));
  int lines = 0;
  for (std::string line; std::getline(records, line);) ++lines;
  EXPECT_EQ(lines, 2);
  std::ifstream in(dir.File("run/summary.json"));
  const nlohmann::json summary = nlohmann::json::parse(in);
  EXPECT_TRUE(summary["interrupted"].get<bool>());
  EXPECT_NE(summary["error"].get<std::string>().find("no room for frame 2"), std::string::npos);
}

}  // namespace
}  // namespace attend
