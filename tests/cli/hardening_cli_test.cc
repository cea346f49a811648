// Hostile and damaged inputs, end to end: each is refused with the exit status of
// SPEC 3.2 and a message that names the file, key, line, frame or option, within seconds, and
// nothing that was already written is lost.
#include <gtest/gtest.h>
#include <sys/mount.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "io/pfm.h"
#include "tests/cli/attend_cli.h"
#include "tests/support/attend_process.h"
#include "tests/support/sequence_maker.h"
#include "tests/support/temp_dir.h"

namespace fs = std::filesystem;

namespace attend {
namespace {

using testing::Attend;
using testing::Contains;
using testing::ReadText;
using testing::Result;

// A YAML alias inside the node it names: yaml-cpp makes it a list that contains itself.
constexpr const char kAliasCycle[] = "a: &x [*x]\n";

// Ten levels of ten aliases each: 10^10 values once expanded, in under a kilobyte.
std::string BillionLaughs() {
  std::string text = "l0: &l0 [x, x, x, x, x, x, x, x, x, x]\n";
  for (int level = 1; level <= 9; ++level) {
    // Appends only: GCC 12 warns falsely (-Wrestrict) on chains of operator+.
    const std::string name = std::to_string(level), below = std::to_string(level - 1);
    text.append("l").append(name).append(": &l").append(name).append(" [");
    for (int k = 0; k < 10; ++k) text.append(k ? ", *l" : "*l").append(below);
    text.append("]\n");
  }
  return text;
}

int Lines(const std::string& path) {
  std::ifstream in(path);
  int lines = 0;
  for (std::string line; std::getline(in, line);) {
    EXPECT_NO_THROW(nlohmann::json::parse(line)) << path << " line " << lines + 1;
    ++lines;
  }
  return lines;
}

// A monocular folder of `frames` JPEG frames (a textured, coloured scene), frame `cut` (if
// >= 0) cut to half its bytes.
std::string JpegFolder(const testing::TempDir& dir, const std::string& name, int frames, int cut) {
  const fs::path folder = dir.File(name);
  fs::create_directories(folder);
  for (int i = 0; i < frames; ++i) {
    cv::Mat image(60, 80, CV_8UC3, cv::Scalar(90, 120, 140));
    cv::randu(image, cv::Scalar::all(60), cv::Scalar::all(200));
    image(cv::Rect(20 + i, 15, 24, 20)).setTo(cv::Scalar(30, 40, 220));
    const std::string path = (folder / ("frame" + std::to_string(100 + i) + ".jpg")).string();
    EXPECT_TRUE(cv::imwrite(path, image));
    if (i == cut) fs::resize_file(path, fs::file_size(path) / 2);
  }
  return folder.string();
}

TEST(Hardening, AYamlAliasCycleIsAConfigurationErrorNamingTheFile) {
  testing::TempDir dir;
  testing::MakeFolderSequence(dir.File("seq"), 2, 32, 24);
  const std::string config = dir.Write("cycle.yaml", kAliasCycle);
  Result r = Attend(dir, {"run", "--config", config, "--sequence", "seq", "--out", "run"});
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_TRUE(Contains(r.err, "cycle.yaml:1")) << r.err;
  EXPECT_TRUE(Contains(r.err, "nested more than 64 levels")) << r.err;
  EXPECT_FALSE(fs::exists(dir.File("run")));

  r = Attend(dir, {"run", "--sequence", "seq", "--out", "run", "--set", "tracker.alpha=&x [*x]"});
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_TRUE(Contains(r.err, "--set tracker.alpha=&x [*x]")) << r.err;

  // The same cycle as a scene file, a sequence.yaml and a skin model.
  r = Attend(dir, {"synth", config, "--out", "synth"});
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_TRUE(Contains(r.err, "cycle.yaml:1")) << r.err;

  dir.Write("seq/sequence.yaml", kAliasCycle);
  r = Attend(dir, {"run", "--sequence", "seq", "--out", "run2"});
  EXPECT_TRUE(r.status == 2 || r.status == 3) << r.status << " " << r.err;
  EXPECT_TRUE(Contains(r.err, "sequence.yaml:1")) << r.err;
  fs::remove(dir.File("seq/sequence.yaml"));

  r = Attend(dir, {"run", "--sequence", "seq", "--out", "run3", "--set",
                   "features.disparity.enabled=false", "--set",
                   "select.skin_model=" + config});
  EXPECT_TRUE(r.status == 2 || r.status == 3) << r.status << " " << r.err;
  EXPECT_TRUE(Contains(r.err, "cycle.yaml:1")) << r.err;
}

TEST(Hardening, ARunConfigurationWithAnAliasCycleIsBadInputForEvalAndCompare) {
  testing::TempDir dir;
  testing::MakeFolderSequence(dir.File("seq"), 2, 32, 24);
  ASSERT_EQ(Attend(dir, {"run", "--sequence", "seq", "--out", "a", "--quiet"}).status, 0);
  ASSERT_EQ(Attend(dir, {"run", "--sequence", "seq", "--out", "b", "--quiet"}).status, 0);
  dir.Write("b/config.yaml", kAliasCycle);
  Result r = Attend(dir, {"compare", "a", "b", "--out", "cmp"});
  EXPECT_TRUE(r.status == 2 || r.status == 3) << r.status << " " << r.err;
  EXPECT_TRUE(Contains(r.err, "b/config.yaml:1")) << r.err;
  r = Attend(dir, {"eval", "b", "--gt", "seq/gt"});
  EXPECT_TRUE(r.status == 2 || r.status == 3) << r.status << " " << r.err;
  EXPECT_TRUE(Contains(r.err, "config.yaml:1")) << r.err;
}

TEST(Hardening, ABillionLaughsIsRefusedWithinSeconds) {
  testing::TempDir dir;
  testing::MakeFolderSequence(dir.File("seq"), 2, 32, 24);
  const std::string config = dir.Write("laughs.yaml", BillionLaughs());
  const auto start = std::chrono::steady_clock::now();
  const Result r = Attend(dir, {"run", "--config", config, "--sequence", "seq", "--out", "run"});
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_TRUE(Contains(r.err, "laughs.yaml")) << r.err;
  EXPECT_TRUE(Contains(r.err, "more than 100000 values")) << r.err;
  EXPECT_LT(seconds, 10.0);
}

TEST(Hardening, APluginCutShortIsRefusedBeforeItIsLoaded) {
  testing::TempDir dir;
  testing::MakeFolderSequence(dir.File("seq"), 2, 32, 24);
  const std::string whole = ReadText(EXAMPLE_PLUGIN);
  ASSERT_GT(whole.size(), 4000u);
  // Cut inside the segments, and cut only the section headers off the end.
  for (const size_t size : {size_t{2000}, whole.size() - 1}) {
    SCOPED_TRACE(size);
    const std::string plugin = dir.Write("cut.so", whole.substr(0, size));
    const Result r = Attend(dir, {"run", "--sequence", "seq", "--out", "run", "--set",
                                  "plugins=[" + plugin + "]"});
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_TRUE(Contains(r.err, "plugin " + plugin + ": is cut short")) << r.err;
  }
}

TEST(Hardening, AJpegFrameCutShortStopsEveryCommandAtThatFrame) {
  testing::TempDir dir;
  const std::string folder = JpegFolder(dir, "frames", 5, 3);
  const std::string cut = folder + "/frame103.jpg";

  Result r = Attend(dir, {"run", "--images", folder, "--out", "run", "--quiet", "--set",
                          "features.disparity.enabled=false"});
  EXPECT_EQ(r.status, 3) << r.err;
  EXPECT_TRUE(Contains(r.err, "frame 3")) << r.err;
  EXPECT_TRUE(Contains(r.err, "frame 3 (" + cut + "): a JPEG file cut short")) << r.err;
  EXPECT_EQ(Lines(dir.File("run/frames.jsonl")), 3);  // frames 0..2 kept
  const nlohmann::json summary = nlohmann::json::parse(ReadText(dir.File("run/summary.json")));
  EXPECT_EQ(summary["frames"], 3);

  r = Attend(dir, {"track", "--images", folder, "--init", "20,15,24,20", "--out", "track"});
  EXPECT_EQ(r.status, 3) << r.err;
  EXPECT_TRUE(Contains(r.err, "frame 3 (" + cut + ")")) << r.err;
  std::istringstream tracks(ReadText(dir.File("track/tracks.csv")));
  int rows = -1;  // the header
  for (std::string line; std::getline(tracks, line);) ++rows;
  EXPECT_EQ(rows, 3);

  r = Attend(dir, {"segment", cut, "--out", "segments"});
  EXPECT_EQ(r.status, 3) << r.err;
  EXPECT_TRUE(Contains(r.err, cut + ": a JPEG file cut short")) << r.err;

  r = Attend(dir, {"disparity", folder + "/frame102.jpg", cut, "--out", "d.pfm"});
  EXPECT_EQ(r.status, 3) << r.err;
  EXPECT_TRUE(Contains(r.err, cut + ": a JPEG file cut short")) << r.err;
  EXPECT_FALSE(fs::exists(dir.File("d.pfm")));
}

TEST(Hardening, APngWithoutItsEndIsRefused) {
  testing::TempDir dir;
  testing::MakeFolderSequence(dir.File("seq"), 4, 32, 24);
  const std::string frame = dir.File("seq/left/000002.png");
  fs::resize_file(frame, fs::file_size(frame) - 6);
  const Result r = Attend(dir, {"run", "--sequence", "seq", "--out", "run", "--quiet"});
  EXPECT_EQ(r.status, 3) << r.err;
  EXPECT_TRUE(Contains(r.err, "frame 2 (")) << r.err;
  EXPECT_TRUE(Contains(r.err, "000002.png): a PNG file cut short")) << r.err;
  EXPECT_EQ(Lines(dir.File("run/frames.jsonl")), 2);
}

TEST(Hardening, PfmHeadersAndChannelsAreChecked) {
  testing::TempDir dir;
  cv::Mat image(24, 32, CV_8UC3, cv::Scalar(50, 100, 150));
  cv::randu(image, cv::Scalar::all(0), cv::Scalar::all(255));
  cv::imwrite(dir.File("l.png"), image);
  cv::imwrite(dir.File("r.png"), image);
  std::string garbage = "Pf\n32abc 24\n-1\n" + std::string(32 * 24 * 4, '\0');
  dir.Write("garbage.pfm", garbage);
  Result r = Attend(dir, {"disparity", "l.png", "r.png", "--out", "d.pfm", "--max-disparity", "8",
                          "--gt", "garbage.pfm"});
  EXPECT_EQ(r.status, 3) << r.err;
  EXPECT_TRUE(Contains(r.err, "garbage.pfm: malformed PFM header")) << r.err;
  EXPECT_TRUE(Contains(r.err, "'32abc'")) << r.err;

  // A three-channel PFM as a run's disparity ground truth for attend eval.
  testing::MakeFolderSequence(dir.File("seq"), 2, 32, 24);
  ASSERT_EQ(Attend(dir, {"run", "--sequence", "seq", "--out", "run", "--quiet", "--set",
                         "output.dump=[features]"})
                .status,
            0);
  fs::create_directories(dir.File("seq/gt/disparity"));
  dir.Write("seq/gt/objects.csv", "frame,id,x,y,w,h,visible_fraction,disparity,kind\n"
                                  "0,1,4,4,8,8,1,,object\n");
  WritePfm(dir.File("seq/gt/disparity/000000.pfm"), cv::Mat(24, 32, CV_32FC3, cv::Scalar::all(1)));
  r = Attend(dir, {"eval", "run", "--gt", "seq/gt"});
  EXPECT_EQ(r.status, 3) << r.err;
  EXPECT_TRUE(Contains(r.err, "000000.pfm: disparity ground truth must be a one-channel PFM"))
      << r.err;
}

TEST(Hardening, HugeFrameNumbersAreOutOfRangeNotAllocations) {
  testing::TempDir dir;
  const std::string header = "frame,id,x,y,w,h,visible_fraction,disparity,kind\n";
  const std::string digits55(55, '9');
  for (const std::string& frame : {std::string("1000000000"), std::string("2147483647"), digits55}) {
    SCOPED_TRACE(frame);
    dir.Write("objects.csv", header + "0,1,1,1,5,5,1,,object\n" + frame + ",1,1,1,5,5,1,,object\n");
    dir.Write("tracks.csv", "frame,id,x,y,w,h,state\n0,1,1,1,5,5,found\n" + frame +
                                ",1,1,1,5,5,found\n");
    Result r = Attend(dir, {"eval-tracking", "tracks.csv", "--gt", "objects.csv"});
    EXPECT_EQ(r.status, 3) << r.err;
    EXPECT_TRUE(Contains(r.err, ".csv:3: frame number out of range")) << r.err;
  }
  // A good tracks.csv against ground truth whose frame number is too large.
  dir.Write("tracks.csv", "frame,id,x,y,w,h,state\n0,1,1,1,5,5,found\n");
  dir.Write("objects.csv", header + digits55 + ",1,1,1,5,5,1,,object\n");
  const Result r = Attend(dir, {"eval-tracking", "tracks.csv", "--gt", "objects.csv"});
  EXPECT_EQ(r.status, 3) << r.err;
  EXPECT_TRUE(Contains(r.err, "objects.csv:2: frame number out of range")) << r.err;
}

TEST(Hardening, AHugeBoxInFramesJsonlIsBadInputForCompare) {
  testing::TempDir dir;
  testing::MakeFolderSequence(dir.File("seq"), 2, 32, 24);
  ASSERT_EQ(Attend(dir, {"run", "--sequence", "seq", "--out", "a", "--quiet"}).status, 0);
  ASSERT_EQ(Attend(dir, {"run", "--sequence", "seq", "--out", "b", "--quiet"}).status, 0);
  dir.Write("b/frames.jsonl",
            R"({"frame":0,"targets":[{"id":1,"bbox":[2147483000,2147483000,2147483000,5],)"
            R"("area":5,"saliency":0.5,"state":"new","kind":"object","similarity":"colour"}],)"
            R"("new":[1],"timings_ms":{}})"
            "\n");
  const Result r = Attend(dir, {"compare", "a", "b", "--out", "cmp"});
  EXPECT_EQ(r.status, 3) << r.err;
  EXPECT_TRUE(Contains(r.err, "frames.jsonl:1")) << r.err;
  EXPECT_TRUE(Contains(r.err, "'bbox x' out of range")) << r.err;
}

TEST(Hardening, SynthRefusesAnImageBeyondItsLimitUpFront) {
  testing::TempDir dir;
  const std::string scene = dir.Write("big.yaml",
                                      "width: 8192\nheight: 8192\nframes: 2\n"
                                      "background: {depth: 6.0, colour: [128, 128, 128]}\n"
                                      "objects: []\n");
  const auto start = std::chrono::steady_clock::now();
  const Result r = Attend(dir, {"synth", scene, "--out", "seq"});
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 10.0);
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_TRUE(Contains(r.err, "big.yaml")) << r.err;
  EXPECT_TRUE(Contains(r.err, "renderer's limit")) << r.err;
  EXPECT_FALSE(fs::exists(dir.File("seq/left")));
}

TEST(Hardening, AnOutOfRangeMaxDisparityNamesTheFlag) {
  testing::TempDir dir;
  cv::Mat image(24, 32, CV_8UC3, cv::Scalar(50, 100, 150));
  cv::imwrite(dir.File("l.png"), image);
  cv::imwrite(dir.File("r.png"), image);
  const Result r =
      Attend(dir, {"disparity", "l.png", "r.png", "--out", "d.pfm", "--max-disparity", "100000"});
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_TRUE(Contains(r.err, "--max-disparity 100000: max_disparity must be <= 1024, got 100000"))
      << r.err;
}

TEST(Hardening, TwoOverridesInConflictAreNamed) {
  testing::TempDir dir;
  testing::MakeFolderSequence(dir.File("seq"), 2, 32, 24);
  const Result r = Attend(dir, {"run", "--sequence", "seq", "--out", "run", "--set",
                                "tracker.epsilon=20", "--set", "tracker.epsilon_max=10"});
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_TRUE(Contains(r.err, "--set tracker.epsilon=20, --set tracker.epsilon_max=10")) << r.err;
}

// A full disk during a run (a 400 KB tmpfs, mounted when the test may; skipped otherwise):
// the message says the disk is full, every line of frames.jsonl is a whole record, and no
// temporary file is left.
TEST(Hardening, AFullDiskStopsTheRunAndKeepsItsFrames) {
  testing::TempDir dir;
  const std::string disk = dir.File("disk");
  fs::create_directories(disk);
  if (mount("tmpfs", disk.c_str(), "tmpfs", 0, "size=400k") != 0) {
    GTEST_SKIP() << "cannot mount a tmpfs here (needs root)";
  }
  struct Unmount {
    std::string path;
    ~Unmount() { umount(path.c_str()); }
  } unmount{disk};
  testing::MakeFolderSequence(dir.File("seq"), 200, 64, 48);
  const Result r = Attend(dir, {"run", "--sequence", "seq", "--out", disk + "/run", "--quiet",
                                "--set", "output.dump=[overlay, saliency]"});
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_TRUE(Contains(r.err, "the disk is full")) << r.err;
  const int kept = Lines(disk + "/run/frames.jsonl");
  EXPECT_GT(kept, 0);
  EXPECT_LT(kept, 200);
  // The summary says how far the run got, or, when it could not be written, the message does.
  if (fs::exists(disk + "/run/summary.json")) {
    const nlohmann::json summary = nlohmann::json::parse(ReadText(disk + "/run/summary.json"));
    EXPECT_EQ(summary["frames"], kept);
    EXPECT_EQ(summary["interrupted"], true);
    EXPECT_TRUE(Contains(summary["error"].get<std::string>(), "the disk is full"));
  } else {
    EXPECT_TRUE(Contains(r.err, "all of them in " + disk + "/run/frames.jsonl")) << r.err;
  }
  // No temporary left: neither a .tmp file nor the NNNNNN.part.* dumps of the frame that was
  // being written when the disk filled (issue 30).
  for (const auto& entry : fs::recursive_directory_iterator(disk)) {
    EXPECT_EQ(entry.path().string().find(".tmp"), std::string::npos) << entry.path();
    EXPECT_EQ(entry.path().string().find(".part"), std::string::npos) << entry.path();
  }
  // No overlay under a frame's name without its record.
  for (const auto& entry : fs::directory_iterator(disk + "/run/overlay")) {
    const std::string name = entry.path().filename().string();
    EXPECT_LT(std::stoi(name.substr(0, 6)), kept) << name;
  }
}

}  // namespace
}  // namespace attend
