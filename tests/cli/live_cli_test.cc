// `attend run` on live sources (docs/LIVE.md), end to end on real GStreamer pipelines of
// videotestsrc: records with their latency, a loop slower than its source dropping frames and
// saying how many, a stereo pair, bad sources refused quickly, a source that stops delivering,
// Ctrl-C, --duration and --frames; and the shipped configuration on a monocular source, live
// or not, leaving the disparity feature out while a configuration of the user's own is refused.
#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <opencv2/videoio.hpp>
#include <sstream>
#include <thread>

#include "tests/cli/attend_cli.h"
#include "tests/support/gstreamer.h"

namespace attend {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
using testing::Attend;
using testing::Contains;
using testing::ReadText;
using testing::Result;

#define SKIP_WITHOUT_GSTREAMER()                                            \
  do {                                                                      \
    const std::string missing = testing::GstreamerMissing();                \
    if (!missing.empty()) GTEST_SKIP() << "no GStreamer here: " << missing; \
  } while (false)

double SecondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

std::vector<nlohmann::json> Frames(const testing::TempDir& dir, const std::string& run) {
  std::vector<nlohmann::json> frames;
  std::istringstream lines(ReadText(dir.File(run + "/frames.jsonl")));
  for (std::string line; std::getline(lines, line);) frames.push_back(nlohmann::json::parse(line));
  return frames;
}

nlohmann::json Summary(const testing::TempDir& dir, const std::string& run) {
  return nlohmann::json::parse(ReadText(dir.File(run + "/summary.json")));
}

// Every frame handed to the loop is a record, and every frame captured was recorded, dropped or
// left in the queue.
void ExpectFramesAccountedFor(const nlohmann::json& summary, size_t records) {
  const nlohmann::json& live = summary.at("live");
  EXPECT_EQ(summary["frames"].get<size_t>(), records);
  EXPECT_EQ(live["frames_captured"].get<int>(),
            summary["frames"].get<int>() + live["frames_dropped"].get<int>() +
                live["frames_unprocessed"].get<int>())
      << summary;
}

TEST(LiveCli, APipelineRunWritesRecordsWithTheirLatency) {
  SKIP_WITHOUT_GSTREAMER();
  testing::TempDir dir;
  const std::string pipeline = testing::TestPipeline(20);
  const Result r = Attend(dir, {"run", "--gst", pipeline, "--out", "run", "--set",
                                "live.queue=30"});
  ASSERT_EQ(r.status, 0) << r.err;
  // The shipped configuration on a monocular source: disparity is left out, with a note.
  EXPECT_TRUE(Contains(r.err, "attend: note: feature 'disparity' needs stereo and is left out"))
      << r.err;
  EXPECT_TRUE(Contains(r.out, "live: 20 frames captured, 0 dropped (queue 30)")) << r.out;
  const std::vector<nlohmann::json> frames = Frames(dir, "run");
  ASSERT_EQ(frames.size(), 20u);
  for (size_t i = 0; i < frames.size(); ++i) {
    EXPECT_EQ(frames[i]["frame"], i);
    ASSERT_TRUE(frames[i].contains("latency_ms")) << frames[i];
    const double latency = frames[i]["latency_ms"].get<double>();
    EXPECT_GT(latency, 0.0);
    EXPECT_LT(latency, 5000.0);
    // Capture to record covers the frame's stages after the read (whose time is mostly the
    // wait for the frame to be captured); the tracking may run beside the features, and each
    // feature's own time is inside theirs.
    double stages = 0.0;
    for (const auto& [stage, ms] : frames[i]["timings_ms"].items()) {
      if (stage != "read" && stage != "track" && stage.rfind("feature.", 0) != 0) {
        stages += ms.get<double>();
      }
    }
    EXPECT_GE(latency, stages - 1.0) << frames[i];
  }
  const nlohmann::json summary = Summary(dir, "run");
  ExpectFramesAccountedFor(summary, frames.size());
  const nlohmann::json& live = summary["live"];
  EXPECT_EQ(live["source"], "GStreamer pipeline '" + pipeline + "'");
  EXPECT_EQ(live["end"], "end of stream");
  EXPECT_EQ(live["frames_dropped"], 0);
  EXPECT_GT(live["latency_ms"]["mean"].get<double>(), 0.0);
  EXPECT_GE(live["latency_ms"]["max"].get<double>(), live["latency_ms"]["mean"].get<double>());
  EXPECT_EQ(summary["interrupted"], false);
  EXPECT_EQ(summary["sequence"]["stereo"], false);
  EXPECT_EQ(summary["features_left_out"], nlohmann::json({"disparity"}));
  // The effective configuration has it off, so that it repeats the run as made.
  EXPECT_TRUE(Contains(ReadText(dir.File("run/config.yaml")), "name: disparity, weight: 1, enabled: false"))
      << ReadText(dir.File("run/config.yaml"));
  EXPECT_TRUE(Contains(ReadText(dir.File("run/config.yaml")), "gst: \"" + pipeline + "\""));
  EXPECT_FALSE(frames[0]["timings_ms"].contains("feature.disparity"));
}

TEST(LiveCli, ALoopSlowerThanItsSourceDropsTheOldestFramesAndSaysHowMany) {
  SKIP_WITHOUT_GSTREAMER();
  testing::TempDir dir;
  // A camera at 200 frames a second; the loop at 640x480 takes several times 5 ms a frame.
  const Result r =
      Attend(dir, {"run", "--gst", testing::TestPipeline(150, 320, 240, 200), "--out", "run",
                   "--quiet", "--set", "sequence.width=640", "--set", "sequence.height=480"});
  ASSERT_EQ(r.status, 0) << r.err;
  const std::vector<nlohmann::json> frames = Frames(dir, "run");
  const nlohmann::json summary = Summary(dir, "run");
  ExpectFramesAccountedFor(summary, frames.size());
  const int dropped = summary["live"]["frames_dropped"].get<int>();
  EXPECT_GT(dropped, 0) << summary;
  EXPECT_EQ(summary["live"]["frames_captured"], 150);
  EXPECT_EQ(summary["live"]["end"], "end of stream");
  // The frame numbers are the source's: the dropped frames are the gaps (frame 0 among them
  // when the queue filled before the loop took its first frame, as under the sanitizers), and
  // the newest frame (the last) is never dropped.
  ASSERT_FALSE(frames.empty());
  EXPECT_EQ(frames.back()["frame"], 149);
  int gaps = frames.front()["frame"].get<int>();
  for (size_t i = 1; i < frames.size(); ++i) {
    const int step = frames[i]["frame"].get<int>() - frames[i - 1]["frame"].get<int>();
    EXPECT_GE(step, 1);
    gaps += step - 1;
  }
  EXPECT_EQ(gaps, dropped);
}

TEST(LiveCli, AStereoPairOfPipelinesKeepsTheDisparityFeature) {
  SKIP_WITHOUT_GSTREAMER();
  testing::TempDir dir;
  const Result r = Attend(dir, {"run", "--gst", testing::TestPipeline(6), "--gst-right",
                                testing::TestPipeline(6), "--out", "run", "--set",
                                "live.queue=10"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_FALSE(Contains(r.err, "note")) << r.err;
  const std::vector<nlohmann::json> frames = Frames(dir, "run");
  ASSERT_EQ(frames.size(), 6u);
  EXPECT_TRUE(frames[0]["timings_ms"].contains("feature.disparity")) << frames[0];
  const nlohmann::json summary = Summary(dir, "run");
  EXPECT_EQ(summary["sequence"]["stereo"], true);
  EXPECT_FALSE(summary.contains("features_left_out"));
  EXPECT_EQ(summary["live"]["frames_captured"], 6);
}

TEST(LiveCli, BadLiveSourcesExitThreeWithinSeconds) {
  testing::TempDir dir;
  Clock::time_point start = Clock::now();
  Result r = Attend(dir, {"run", "--camera", "97", "--out", "run"});
  EXPECT_EQ(r.status, 3) << r.err;
  EXPECT_TRUE(Contains(r.err, "attend: error: camera 97: no such device /dev/video97")) << r.err;
  EXPECT_LT(SecondsSince(start), 5.0);
  EXPECT_FALSE(fs::exists(dir.File("run")));

  if (!testing::GstreamerMissing().empty()) return;  // the pipelines need GStreamer
  // A missing element, a syntax error, and a text that GStreamer makes a pipeline of that never
  // starts (given up after live.timeout_s, 1 s here). The bound is for a hang: a run warms up
  // before its source opens (docs/LIVE.md), which takes seconds under the sanitizers.
  for (const std::string pipeline :
       {"videotestsrc ! nosuchelement", "videotestsrc ! appsink ! (", "this is not a pipeline"}) {
    SCOPED_TRACE(pipeline);
    start = Clock::now();
    r = Attend(dir, {"run", "--gst", pipeline, "--out", "run", "--set", "live.timeout_s=1"});
    EXPECT_EQ(r.status, 3) << r.err;
    EXPECT_TRUE(Contains(r.err, "attend: error: GStreamer pipeline '" + pipeline + "': "))
        << r.err;
    EXPECT_TRUE(Contains(r.err, "cannot be opened") || Contains(r.err, "did not start"))
        << r.err;
    EXPECT_LT(SecondsSince(start), 5.0);
    EXPECT_FALSE(fs::exists(dir.File("run")));
  }
  // Usage errors: two kinds of source for one view, a duration without a live source.
  r = Attend(dir, {"run", "--camera", "0", "--gst", "videotestsrc"});
  EXPECT_EQ(r.status, 2) << r.err;
  r = Attend(dir, {"run", "--video", "v.avi", "--duration", "2"});
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_TRUE(Contains(r.err, "--duration bounds a live source")) << r.err;
  r = Attend(dir, {"run", "--gst", "videotestsrc", "--set", "live.queue=0"});
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_TRUE(Contains(r.err, "live.queue")) << r.err;
}

TEST(LiveCli, ASourceThatStopsDeliveringEndsTheRunAfterTheTimeout) {
  SKIP_WITHOUT_GSTREAMER();
  testing::TempDir dir;
  // Three frames, then nothing, without an end of stream: a camera that stopped delivering.
  const std::string stalling = testing::StallingPipeline(3);
  const Clock::time_point start = Clock::now();
  const Result r = Attend(dir, {"run", "--gst", stalling, "--out", "run", "--quiet", "--set",
                                "live.timeout_s=1"});
  EXPECT_LT(SecondsSince(start), 8.0);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(Contains(r.err, "attend: warning: GStreamer pipeline '" + stalling +
                                  "' delivered no frame for 1 s (live.timeout_s): it has "
                                  "stopped; the run ends with the 3 frames it had"))
      << r.err;
  const nlohmann::json summary = Summary(dir, "run");
  EXPECT_EQ(summary["frames"], 3);
  EXPECT_EQ(summary["interrupted"], false);
  EXPECT_EQ(summary["live"]["end"], "timeout");
  EXPECT_TRUE(Contains(summary["live"]["why"].get<std::string>(), "delivered no frame"));
  EXPECT_EQ(Frames(dir, "run").size(), 3u);
}

TEST(LiveCli, CtrlCEndsALiveRunWithACompleteSummary) {
  SKIP_WITHOUT_GSTREAMER();
  testing::TempDir dir;
  const pid_t pid = testing::StartAttend(
      dir, {"run", "--gst", testing::TestPipeline(-1), "--out", "run", "--quiet"});
  const Clock::time_point deadline = Clock::now() + std::chrono::seconds(30);
  while (Clock::now() < deadline && (!fs::exists(dir.File("run/frames.jsonl")) ||
                                     fs::file_size(dir.File("run/frames.jsonl")) == 0)) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  const Clock::time_point interrupted = Clock::now();
  kill(pid, SIGINT);
  const Result r = testing::Wait(dir, pid);
  EXPECT_LT(SecondsSince(interrupted), 3.0);
  EXPECT_EQ(r.status, 130) << r.err;
  const nlohmann::json summary = Summary(dir, "run");
  EXPECT_EQ(summary["interrupted"], true);
  EXPECT_EQ(summary["live"]["end"], "stopped");
  const std::vector<nlohmann::json> frames = Frames(dir, "run");
  EXPECT_GE(frames.size(), 1u);
  ExpectFramesAccountedFor(summary, frames.size());
}

TEST(LiveCli, DurationAndFramesBoundALiveRun) {
  SKIP_WITHOUT_GSTREAMER();
  testing::TempDir dir;
  const Clock::time_point start = Clock::now();
  Result r = Attend(dir, {"run", "--gst", testing::TestPipeline(-1), "--duration", "0.7",
                          "--out", "run", "--quiet"});
  EXPECT_LT(SecondsSince(start), 8.0);
  ASSERT_EQ(r.status, 0) << r.err;
  nlohmann::json summary = Summary(dir, "run");
  EXPECT_EQ(summary["live"]["end"], "duration");
  EXPECT_GE(summary["frames"].get<int>(), 1);
  EXPECT_LE(summary["live"]["frames_captured"].get<int>(), 40);  // 30 a second for 0.7 s
  // The effective configuration holds the duration, so that it repeats the run.
  const std::string config = ReadText(dir.File("run/config.yaml"));
  const size_t at = config.find("duration_s: ");
  ASSERT_NE(at, std::string::npos) << config;
  EXPECT_NEAR(std::stod(config.substr(at + 12)), 0.7, 1e-9) << config;

  r = Attend(dir, {"run", "--gst", testing::TestPipeline(-1), "--frames", "3:12", "--out",
                   "run2", "--quiet", "--set", "live.queue=20"});
  ASSERT_EQ(r.status, 0) << r.err;
  summary = Summary(dir, "run2");
  EXPECT_EQ(summary["live"]["end"], "frame range");
  EXPECT_EQ(summary["live"]["frames_captured"], 10);
  const std::vector<nlohmann::json> frames = Frames(dir, "run2");
  ASSERT_FALSE(frames.empty());
  EXPECT_EQ(frames.front()["frame"], 3);
  EXPECT_EQ(frames.back()["frame"], 12);
}

// A monocular Motion-JPEG video of `frames` textured frames.
std::string WriteVideo(const testing::TempDir& dir, int frames) {
  const std::string path = dir.File("mono.avi");
  cv::VideoWriter writer(path, cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), 10, cv::Size(64, 48));
  EXPECT_TRUE(writer.isOpened());
  cv::RNG rng(3);
  for (int i = 0; i < frames; ++i) {
    cv::Mat frame(48, 64, CV_8UC3);
    rng.fill(frame, cv::RNG::UNIFORM, 0, 255);
    writer.write(frame);
  }
  return path;
}

TEST(LiveCli, TheShippedConfigurationLeavesDisparityOutOnAMonocularVideo) {
  testing::TempDir dir;
  WriteVideo(dir, 3);
  Result r = Attend(dir, {"run", "--video", "mono.avi", "--out", "run"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(Contains(r.err, "attend: note: feature 'disparity' needs stereo and is left out: "
                              "the source is monocular"))
      << r.err;
  EXPECT_EQ(Frames(dir, "run").size(), 3u);
  nlohmann::json summary = Summary(dir, "run");
  EXPECT_EQ(summary["features_left_out"], nlohmann::json({"disparity"}));
  EXPECT_FALSE(summary.contains("live"));
  EXPECT_FALSE(Frames(dir, "run")[0].contains("latency_ms"));
  // --quiet keeps the note to itself; naming the shipped file is the shipped configuration.
  r = Attend(dir, {"run", "--video", "mono.avi", "--out", "run2", "--quiet", "--config",
                   testing::ProjectRoot() + "/configs/default.yaml"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err, "");
  // The effective configuration has disparity off and repeats the run as the user's own.
  r = Attend(dir, {"run", "--config", "run/config.yaml", "--out", "again", "--quiet"});
  ASSERT_EQ(r.status, 0) << r.err;

  // A configuration of the user's own, or an override of the features, that asks for
  // disparity still gets the error, and leaves nothing behind.
  dir.Write("mine.yaml", "features:\n  - {name: colour_contrast}\n  - {name: disparity}\n");
  for (const std::vector<std::string>& extra :
       {std::vector<std::string>{"--config", "mine.yaml"},
        std::vector<std::string>{"--set", "features.disparity.weight=2"}}) {
    std::vector<std::string> args = {"run", "--video", "mono.avi", "--out", "refused"};
    args.insert(args.end(), extra.begin(), extra.end());
    r = Attend(dir, args);
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_TRUE(Contains(r.err, "feature 'disparity' needs a stereo sequence")) << r.err;
    EXPECT_FALSE(fs::exists(dir.File("refused")));
  }
}

}  // namespace
}  // namespace attend
