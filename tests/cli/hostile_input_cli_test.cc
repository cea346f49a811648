// Bad input, round 3 (issue 46), end to end: concurrent writers of one run folder, empty source
// paths, hostile frame records, non-finite numbers on the command line, deep and huge YAML,
// files that are not regular files. Each is refused at once with SPEC 3.2's exit status and a
// message that names the culprit, and nothing already written is lost.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "tests/cli/attend_cli.h"
#include "tests/support/attend_process.h"
#include "tests/support/gstreamer.h"
#include "tests/support/temp_dir.h"

namespace fs = std::filesystem;

namespace attend {
namespace {

using testing::Attend;
using testing::Contains;
using testing::ReadText;
using testing::Result;
using testing::TempDir;

using Clock = std::chrono::steady_clock;

int Lines(const std::string& path) {
  std::ifstream in(path);
  int lines = 0;
  for (std::string line; std::getline(in, line);) lines += line.empty() ? 0 : 1;
  return lines;
}

// Waits up to 60 s for `path` to hold at least `lines` lines.
bool WaitForLines(const std::string& path, int lines) {
  const auto end = Clock::now() + std::chrono::seconds(60);
  while (Clock::now() < end) {
    if (Lines(path) >= lines) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return false;
}

// A run that lasts: a live test pipeline of 10 frames a second for about 3 s.
std::vector<std::string> SlowRun(const std::string& out) {
  return {"run", "--gst", testing::TestPipeline(30, 160, 120, 10), "--out", out, "--quiet",
          "--overwrite", "--set", "live.queue=30"};
}

TEST(HostileInput, ASecondRunIntoAFolderInUseIsRefusedAndTheFirstKeepsItsRecords) {
  const std::string missing = testing::GstreamerMissing();
  if (!missing.empty()) GTEST_SKIP() << "no GStreamer here: " << missing;
  TempDir dir;
  const pid_t first = testing::StartAttend(dir, SlowRun("run"));
  ASSERT_TRUE(WaitForLines(dir.File("run/frames.jsonl"), 2)) << ReadText(dir.File("stderr"));
  TempDir second_dir;
  const Result second = Attend(second_dir, SlowRun(dir.File("run")));
  EXPECT_EQ(second.status, 2) << second.err;
  EXPECT_TRUE(Contains(second.err, dir.File("run") + ": in use by another attend run (pid " +
                                       std::to_string(first)))
      << second.err;
  const Result r = testing::Wait(dir, first);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(Lines(dir.File("run/frames.jsonl")), 30);
  const nlohmann::json summary = nlohmann::json::parse(ReadText(dir.File("run/summary.json")));
  EXPECT_EQ(summary["frames"], 30) << summary.dump();
  EXPECT_FALSE(fs::exists(dir.File("run/.attend-lock")));  // released at the end
}

TEST(HostileInput, TheLockOfAKilledRunIsTakenOverWithANote) {
  const std::string missing = testing::GstreamerMissing();
  if (!missing.empty()) GTEST_SKIP() << "no GStreamer here: " << missing;
  TempDir dir;
  const pid_t first = testing::StartAttend(dir, SlowRun("run"));
  ASSERT_TRUE(WaitForLines(dir.File("run/frames.jsonl"), 1)) << ReadText(dir.File("stderr"));
  ASSERT_EQ(kill(first, SIGKILL), 0);
  testing::Wait(dir, first);
  ASSERT_TRUE(fs::exists(dir.File("run/.attend-lock")));
  const Result r = Attend(dir, {"run", "--gst", testing::TestPipeline(3), "--out", "run",
                                "--overwrite", "--quiet"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(Contains(r.err, "took over the lock of an earlier run that ended without "
                              "releasing it (pid " + std::to_string(first)))
      << r.err;
  EXPECT_EQ(Lines(dir.File("run/frames.jsonl")), 3);
}

TEST(HostileInput, AnEmptySourcePathIsRefusedNotReplacedByTheBundledSequence) {
  TempDir dir;
  for (const std::string option : {"--video", "--gst", "--sequence", "--images", "--left"}) {
    const Result r = Attend(dir, {"run", option, "", "--out", "run"});
    EXPECT_EQ(r.status, 2) << option << ": " << r.err;
    EXPECT_TRUE(Contains(r.err, "argument 3 (the value of " + option + ") is empty")) << r.err;
  }
  const Result r = Attend(dir, {"run", "--video=", "--out", "run"});
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_TRUE(Contains(r.err, "argument 2 (--video) is empty")) << r.err;
  EXPECT_FALSE(fs::exists(dir.File("run")));
}

TEST(HostileInput, NonFiniteNumbersOnTheCommandLineAreRefused) {
  TempDir dir;
  Result r = Attend(dir, {"run", "--gst", "videotestsrc", "--duration", "nan"});
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_TRUE(Contains(r.err, "--duration: 'nan' is not a finite number")) << r.err;
  r = Attend(dir, {"fit-weights", "--step", "nan", "x"});
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_TRUE(Contains(r.err, "--step: 'nan' is not a finite number")) << r.err;
  r = Attend(dir, {"eval-fixations", "m", "--dataset", "d", "--sigma", "-inf"});
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_TRUE(Contains(r.err, "--sigma: '-inf' is not a finite number")) << r.err;
}

// A valid run folder of `frames` records, each with the given targets JSON.
std::string RunFolder(const TempDir& dir, const std::string& name, const std::string& targets,
                      int frames = 2) {
  const fs::path run = dir.path() / name;
  fs::create_directories(run);
  std::ofstream out(run / "frames.jsonl");
  for (int f = 0; f < frames; ++f) {
    out << "{\"frame\":" << f << ",\"targets\":" << targets
        << ",\"new\":[],\"timings_ms\":{\"total\":1.0}}\n";
  }
  std::ofstream(run / "config.yaml") << "threads: 1\n";
  return run.string();
}

std::string Target(int id, int x, const std::string& state = "tracked") {
  return "{\"id\":" + std::to_string(id) + ",\"bbox\":[" + std::to_string(x) +
         ",10,20,20],\"area\":400,\"saliency\":0.5,\"state\":\"" + state +
         "\",\"kind\":\"region\",\"similarity\":\"colour\"}";
}

// A ground truth folder with one object in frames 0 and 1.
std::string Truth(const TempDir& dir) {
  fs::create_directories(dir.path() / "gt");
  dir.Write("gt/objects.csv",
            "frame,id,x,y,w,h,visible_fraction,disparity,kind\n0,1,10,10,20,20,1,5,object\n"
            "1,1,10,10,20,20,1,5,object\n");
  return dir.File("gt");
}

TEST(HostileInput, ATargetIdTwiceInOneRecordIsRefusedByEvalCompareAndReport) {
  TempDir dir;
  const std::string twice = RunFolder(dir, "twice", "[" + Target(3, 10) + "," + Target(3, 40) + "]");
  const std::string once = RunFolder(dir, "once", "[" + Target(3, 10) + "]");
  const std::string gt = Truth(dir);
  const std::string expected = "frames.jsonl:1: not a frame record (target id 3 twice (targets 1 "
                               "and 2): a target is recorded once a frame, and once more only "
                               "when it ended there and was resumed under its id)";
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"eval", twice, "--gt", gt},
        std::vector<std::string>{"compare", once, twice, "--out", "cmp"},
        std::vector<std::string>{"report", twice, "--out", "rep"}}) {
    const Result r = Attend(dir, args);
    EXPECT_EQ(r.status, 3) << args[0] << ": " << r.err;
    EXPECT_TRUE(Contains(r.err, expected)) << args[0] << ": " << r.err;
  }
  EXPECT_EQ(Attend(dir, {"eval", once, "--gt", gt}).status, 0);
  // A target released in a frame and resumed from its object file there under its id (as
  // configs/people.yaml does) has one box in it: that record is read.
  const std::string resumed = RunFolder(
      dir, "resumed", "[" + Target(3, 10, "released") + "," + Target(3, 40, "resumed") + "]");
  const Result r = Attend(dir, {"eval", resumed, "--gt", gt});
  EXPECT_EQ(r.status, 0) << r.err;
  // Two boxes of one id are refused whatever their states.
  const std::string two_boxes = RunFolder(
      dir, "two_boxes", "[" + Target(3, 10, "resumed") + "," + Target(3, 40, "new") + "]");
  EXPECT_EQ(Attend(dir, {"eval", two_boxes, "--gt", gt}).status, 3);
}

TEST(HostileInput, RecordsThatAreAFolderOrTooManyTargetsAreRefusedAtOnce) {
  TempDir dir;
  const std::string gt = Truth(dir);
  const std::string folder = dir.File("folder");
  fs::create_directories(folder + "/frames.jsonl");
  std::ofstream(folder + "/config.yaml") << "threads: 1\n";
  Result r = Attend(dir, {"eval", folder, "--gt", gt});
  EXPECT_EQ(r.status, 3) << r.err;
  EXPECT_TRUE(Contains(r.err, "frames.jsonl: the frame records is a folder, not a file")) << r.err;

  std::string many = "[";
  for (int id = 0; id <= 10000; ++id) many += (id ? "," : "") + Target(id, id % 100);
  const std::string crowded = RunFolder(dir, "crowded", many + "]", 1);
  const auto start = Clock::now();
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"eval", crowded, "--gt", gt},
        std::vector<std::string>{"report", crowded, "--out", "rep"}}) {
    r = Attend(dir, args);
    EXPECT_EQ(r.status, 3) << args[0] << ": " << r.err;
    EXPECT_TRUE(Contains(r.err, "frames.jsonl:1: not a frame record (10001 targets, more than "
                                "10000 (docs/LIMITS.md))"))
        << r.err;
  }
  EXPECT_LT(Clock::now() - start, std::chrono::seconds(20));
  EXPECT_FALSE(fs::exists(dir.File("rep")));
}

// IDF1's identity assignment was one matrix of every object and target id of the sequence:
// 300,000 object ids took 24 GB before the kernel killed it. It is now solved by groups of ids
// that overlap, and a frame of more than 10,000 objects is refused.
TEST(HostileInput, ManyIdsAreScoredInBoundedTimeAndMemory) {
  TempDir dir;
  fs::create_directories(dir.path() / "gt");
  std::ofstream objects(dir.File("gt/objects.csv"));
  objects << "frame,id,x,y,w,h,visible_fraction,disparity,kind\n";
  const fs::path run = dir.path() / "run";
  fs::create_directories(run);
  std::ofstream records(run / "frames.jsonl");
  for (int frame = 0; frame < 4000; ++frame) {
    records << "{\"frame\":" << frame << ",\"targets\":[";
    for (int k = 0; k < 10; ++k) {
      const int id = frame * 10 + k;  // 40,000 object ids, each seen once
      objects << frame << "," << id << "," << 30 * k << ",10,20,20,1,5,object\n";
      if (k < 3) records << (k ? "," : "") << Target(id, 30 * k);
    }
    records << "],\"new\":[],\"timings_ms\":{\"total\":1.0}}\n";
  }
  objects.close();
  records.close();
  std::ofstream(run / "config.yaml") << "threads: 1\n";
  const auto start = Clock::now();
  Result r = Attend(dir, {"eval", run.string(), "--gt", dir.File("gt")});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_LT(Clock::now() - start, std::chrono::seconds(60));
  const nlohmann::json scores = nlohmann::json::parse(r.out);
  EXPECT_EQ(scores["mot"]["iou_0.5"]["IDTP"], 12000);
  EXPECT_NEAR(scores["mot"]["iou_0.5"]["IDF1"].get<double>(), 2.0 * 12000 / (24000 + 28000), 1e-12);

  std::ofstream crowded(dir.File("gt/objects.csv"));
  crowded << "frame,id,x,y,w,h,visible_fraction,disparity,kind\n";
  for (int id = 0; id <= 10000; ++id) crowded << "0," << id << ",10,10,20,20,1,5,object\n";
  crowded.close();
  r = Attend(dir, {"eval", run.string(), "--gt", dir.File("gt")});
  EXPECT_EQ(r.status, 3) << r.err;
  EXPECT_TRUE(Contains(r.err, "objects.csv:10002: more than 10000 objects in frame 0")) << r.err;
}

TEST(HostileInput, DeepOrHugeYamlIsNamedNotEchoed) {
  TempDir dir;
  const std::string deep = dir.Write("deep.yaml", "a: " + std::string(600, '[') +
                                                      std::string(600, ']') + "\n");
  Result r = Attend(dir, {"run", "--config", deep, "--out", "run"});
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_TRUE(Contains(r.err, deep + ":1:")) << r.err;
  EXPECT_TRUE(Contains(r.err, "levels deep; a configuration is at most 64 levels deep")) << r.err;

  // A value of 1 MB: the message names the file and key, and is not 1 MB long.
  const std::string huge = dir.Write("huge.yaml", "threads: " + std::string(1 << 20, '7') + "x\n");
  r = Attend(dir, {"run", "--config", huge, "--out", "run"});
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_TRUE(Contains(r.err, huge)) << r.err.substr(0, 300);
  EXPECT_TRUE(Contains(r.err, "threads")) << r.err.substr(0, 300);
  EXPECT_LT(r.err.size(), 8000u);

  // A --set of more than 64 KB.
  r = Attend(dir, {"run", "--set", "threads=" + std::string(70000, '1'), "--out", "run"});
  EXPECT_EQ(r.status, 2) << r.err.substr(0, 300);
  EXPECT_TRUE(Contains(r.err, "more than 64 KB")) << r.err.substr(0, 300);
  EXPECT_LT(r.err.size(), 1000u);
  EXPECT_FALSE(fs::exists(dir.File("run")));
}

TEST(HostileInput, ConfigurationsAndPluginsMustBeRegularFiles) {
  TempDir dir;
  const std::string fifo = dir.File("fifo.yaml");
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  const auto start = Clock::now();
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"/dev/zero", "/dev/zero: the YAML file is a character device, not a file"},
      {fifo, fifo + ": the YAML file is a fifo (named pipe), not a file"},
      {dir.path().string(), dir.path().string() + ": the YAML file is a folder, not a file"}};
  for (const auto& [path, message] : cases) {
    Result r = Attend(dir, {"run", "--config", path, "--out", "run"});
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_TRUE(Contains(r.err, message)) << r.err;
    // The skin model named in the configuration.
    r = Attend(dir, {"run", "--set", "features=[{name: skin, model: " + path + "}]", "--out",
                     "run"});
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_TRUE(Contains(r.err, message)) << r.err;
    // A plugin.
    r = Attend(dir, {"run", "--set", "plugins=[" + path + "]", "--out", "run"});
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_TRUE(Contains(r.err, "plugins.0: " + path + ": the plugin is ")) << r.err;
  }
  EXPECT_LT(Clock::now() - start, std::chrono::seconds(30));
  // A configuration over the size cap.
  const std::string big = dir.File("big.yaml");
  fs::resize_file(dir.Write("big.yaml", "# "), (16u << 20) + 1);
  const Result r = Attend(dir, {"run", "--config", big, "--out", "run"});
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_TRUE(Contains(r.err, big + ": the YAML file is 16777217 bytes, more than 16 MB")) << r.err;
  EXPECT_FALSE(fs::exists(dir.File("run")));
}

TEST(HostileInput, APluginsNaNMapIsThePluginsFailureNamingThePixel) {
  TempDir dir;
  const std::string scene = (fs::path(testing::ProjectRoot()) / "sequences" / "lab.yaml").string();
  ASSERT_EQ(Attend(dir, {"synth", scene, "--out", "seq", "--frames", "3"}).status, 0);
  const Result r = Attend(dir, {"run", "--sequence", "seq", "--out", "run", "--quiet", "--set",
                                std::string("plugins=[") + NOT_FINITE_PLUGIN + "]", "--set",
                                "features=[{name: colour_contrast}, {name: not_finite}]"});
  EXPECT_EQ(r.status, 4) << r.err;
  EXPECT_TRUE(Contains(r.err, "feature 'not_finite' (")) << r.err;
  EXPECT_TRUE(Contains(r.err, "returned a map with NaN or infinite values (first at x 20, y 10; "
                              "1 pixels)"))
      << r.err;
  EXPECT_EQ(Lines(dir.File("run/frames.jsonl")), 1);  // the frame before is kept
}

}  // namespace
}  // namespace attend
