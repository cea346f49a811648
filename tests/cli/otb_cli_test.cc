// attend eval-tracking --otb end to end: the report of a drawn OTB sequence, its summary, its
// tracks re-scored by attend eval-tracking, and the exit statuses of its errors (SPEC 3.2;
// docs/TRACKING.md, "The OTB evaluation").
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "tests/cli/attend_cli.h"
#include "tests/support/attend_process.h"
#include "tests/support/otb_maker.h"
#include "tests/support/temp_dir.h"

namespace attend {
namespace {

namespace fs = std::filesystem;
using testing::Attend;
using testing::Contains;
using testing::MakeOtbSequence;
using testing::ReadText;
using testing::Result;
using testing::TempDir;

std::string Joined(const std::vector<std::string>& args) {
  std::string text;
  for (const std::string& arg : args) text += (text.empty() ? "" : " ") + arg;
  return text;
}

// DIR/otb/Slide: a square sliding 2 px right a frame, 10 frames of 160x120.
void MakeSlide(const TempDir& dir) {
  MakeOtbSequence(dir.File("otb/Slide"), 10, cv::Size(160, 120), {{{20, 40}, {2, 0}, 24}});
}

TEST(EvalOtbCommand, WritesTheReportAndItsTracksRescoreToTheSameAuc) {
  TempDir dir;
  MakeSlide(dir);
  const Result r = Attend(dir, {"eval-tracking", "--otb", "otb", "--out", "report", "--trackers",
                                "attend,kcf", "--set", "tracker.mode=bounded", "--set",
                                "tracker.occlusion=false"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(Contains(r.out, "OTB one-pass evaluation: 1 sequences, 10 frames")) << r.out;
  EXPECT_TRUE(Contains(r.out, "bip, mode bounded, occlusion off")) << r.out;
  EXPECT_TRUE(Contains(r.out, "report/index.html")) << r.out;
  EXPECT_TRUE(Contains(r.err, "Slide: 10 frames")) << r.err;
  const nlohmann::json results = nlohmann::json::parse(ReadText(dir.File("report/results.json")));
  EXPECT_EQ(results["trackers"][0]["options"]["occlusion"], false);
  EXPECT_TRUE(Contains(results["command"].get<std::string>(), "--trackers attend,kcf"));
  const double auc = results["sequences"][0]["trackers"]["attend"]["success_auc"].get<double>();

  const Result scored = Attend(dir, {"eval-tracking", "report/tracks/attend/Slide.csv", "--gt",
                                     "otb/Slide/groundtruth_rect.txt"});
  ASSERT_EQ(scored.status, 0) << scored.err;
  const nlohmann::json report = nlohmann::json::parse(scored.out);
  EXPECT_DOUBLE_EQ(report["targets"][0]["success_auc"].get<double>(), auc);
  EXPECT_EQ(report["targets"][0]["precision"].size(), 51u);
}

TEST(EvalOtbCommand, UsageErrorsExitTwo) {
  TempDir dir;
  MakeSlide(dir);
  const auto status = [&](const std::vector<std::string>& args, const std::string& says) {
    std::vector<std::string> full = {"eval-tracking"};
    full.insert(full.end(), args.begin(), args.end());
    const Result r = Attend(dir, full);
    EXPECT_EQ(r.status, 2) << Joined(args) << ": " << r.err;
    EXPECT_TRUE(Contains(r.err, says)) << Joined(args) << ": " << r.err;
  };
  status({"t.csv", "--gt", "g.txt", "--otb", "otb", "--out", "o"}, "do not mix");
  status({"--otb", "otb"}, "--out REPORT is required");
  status({"--out", "o", "--trackers", "kcf"}, "without --otb");
  status({}, "give either TRACKS --gt GT");
  status({"--otb", "otb", "--out", "o", "--trackers", "kcf,mil"}, "unknown tracker 'mil'");
  status({"--otb", "otb", "--out", "o", "--set", "select.max_new=2"}, "takes only tracker.");
  status({"--otb", "otb", "--out", "o", "--set", "tracker.t_colur=3"}, "did you mean 't_colour'");
  status({"--otb", "otb", "--out", "o", "--config", "missing.yaml"}, "missing.yaml");
  status({"--otb", "otb", "--out", "o", "--sequences", "Slid"}, "no sequence 'Slid'");
  fs::create_directories(dir.File("full"));
  dir.Write("full/mine.txt", "x");
  status({"--otb", "otb", "--out", "full", "--trackers", "kcf"}, "not empty");
  EXPECT_FALSE(fs::exists(dir.File("o")));
}

TEST(EvalOtbCommand, BadInputExitsThreeNamingTheFileOrFrame) {
  TempDir dir;
  const auto status = [&](const std::string& otb, const std::string& says) {
    const Result r =
        Attend(dir, {"eval-tracking", "--otb", otb, "--out", "o", "--trackers", "kcf"});
    EXPECT_EQ(r.status, 3) << otb << ": " << r.err;
    EXPECT_TRUE(Contains(r.err, says)) << otb << ": " << r.err;
  };
  status("nowhere", "nowhere: no such folder");
  fs::create_directories(dir.File("empty/sub"));
  status("empty", "no OTB sequence");
  MakeSlide(dir);
  dir.Write("otb/Slide/groundtruth_rect.txt", "21,41,24,24\n23,41,24\n");
  status("otb", "groundtruth_rect.txt:2");
  EXPECT_FALSE(fs::exists(dir.File("o")));
  MakeSlide(dir);
  dir.Write("otb/Slide/img/0005.jpg", "");
  status("otb/Slide", "0005.jpg");
  EXPECT_FALSE(fs::exists(dir.File("o/results.json")));
}

}  // namespace
}  // namespace attend
