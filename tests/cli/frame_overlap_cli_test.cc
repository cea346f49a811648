// attend run with two threads works on two frames at once (pipeline/run.cc,
// RunFramesOverlapped): its records, its dumped maps and what it keeps when a frame is bad are
// those of one thread.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <sstream>

#include "io/pfm.h"
#include "tests/cli/attend_cli.h"
#include "tests/support/attend_process.h"
#include "tests/support/temp_dir.h"

namespace fs = std::filesystem;

namespace attend {
namespace {

using testing::Attend;
using testing::Result;

// The records of dir/run/frames.jsonl without their timings (which differ from run to run).
std::vector<nlohmann::json> Records(const testing::TempDir& dir, const std::string& run) {
  std::ifstream in(dir.File(run + "/frames.jsonl"));
  std::vector<nlohmann::json> records;
  for (std::string line; std::getline(in, line);) {
    nlohmann::json record = nlohmann::json::parse(line);
    record.erase("timings_ms");
    records.push_back(record);
  }
  return records;
}

cv::Mat Map(const testing::TempDir& dir, const std::string& run, const std::string& kind,
            int frame) {
  std::ostringstream name;
  name << run << "/" << kind << "/" << std::setw(6) << std::setfill('0') << frame << ".pfm";
  return ReadPfm(dir.File(name.str()));
}

void RenderLab(const testing::TempDir& dir, int frames) {
  const Result r = Attend(dir, {"synth", testing::ProjectRoot() + "/sequences/lab.yaml", "--out",
                                "seq", "--frames", std::to_string(frames)});
  ASSERT_EQ(r.status, 0) << r.err;
}

TEST(FrameOverlap, TwoThreadsGiveTheRecordsAndMapsOfOne) {
  testing::TempDir dir;
  RenderLab(dir, 16);
  for (const std::string threads : {"1", "2", "3"}) {
    const Result r = Attend(dir, {"run", "--sequence", "seq", "--out", "t" + threads, "--quiet",
                                  "--set", "output.dump=[saliency, inhibition, features]",
                                  "--set", "threads=" + threads});
    ASSERT_EQ(r.status, 0) << r.err;
  }
  const std::vector<nlohmann::json> one = Records(dir, "t1");
  ASSERT_EQ(one.size(), 16u);
  int targets = 0;
  for (const nlohmann::json& record : one) targets += record["targets"].size();
  EXPECT_GT(targets, 16);
  for (const std::string run : {"t2", "t3"}) {
    EXPECT_EQ(Records(dir, run), one) << run;
    // Each frame's dumps are that frame's maps, not the next frame's (which the second thread
    // is working on when they are written).
    for (int frame = 0; frame < 16; ++frame) {
      for (const std::string kind : {"saliency", "inhibition", "features/disparity"}) {
        EXPECT_EQ(cv::norm(Map(dir, "t1", kind, frame), Map(dir, run, kind, frame),
                           cv::NORM_INF),
                  0.0)
            << run << " " << kind << " " << frame;
      }
    }
  }
}

// A bad frame stops the run where one thread stops: after the frames before it are recorded,
// with the same message and exit status, although the second thread read it early.
TEST(FrameOverlap, ABadFrameStopsTwoThreadsWhereItStopsOne) {
  testing::TempDir dir;
  RenderLab(dir, 10);
  std::ofstream(dir.File("seq/left/000006.png"), std::ios::binary) << "not a png";
  Result results[2];
  for (int i = 0; i < 2; ++i) {
    results[i] = Attend(dir, {"run", "--sequence", "seq", "--out", "t" + std::to_string(i + 1),
                              "--quiet", "--set", "threads=" + std::to_string(i + 1)});
  }
  EXPECT_NE(results[0].status, 0);
  EXPECT_EQ(results[1].status, results[0].status);
  EXPECT_EQ(results[1].err, results[0].err);
  EXPECT_NE(results[0].err.find("000006.png"), std::string::npos) << results[0].err;
  const std::vector<nlohmann::json> one = Records(dir, "t1");
  EXPECT_EQ(one.size(), 6u);
  EXPECT_EQ(Records(dir, "t2"), one);
  for (const std::string run : {"t1", "t2"}) {
    std::ifstream in(dir.File(run + "/summary.json"));
    const nlohmann::json summary = nlohmann::json::parse(in);
    EXPECT_EQ(summary["frames"], 6) << run;
  }
}

}  // namespace
}  // namespace attend
