// The OTB evaluation (app/evaluate_otb.h) end to end on drawn sequences in the OTB layout,
// whose true boxes are known by construction: what it finds, scores and writes, and how it
// refuses bad input.
#include "app/evaluate_otb.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>

#include "app/score_tracks.h"
#include "app/track_sequence.h"
#include "tests/support/attend_process.h"
#include "tests/support/error_message.h"
#include "tests/support/otb_maker.h"
#include "tests/support/temp_dir.h"
#include "util/error.h"

namespace attend {
namespace {

namespace fs = std::filesystem;
using testing::DrawnSquare;
using testing::ErrorOf;
using testing::MakeOtbSequence;
using testing::ReadText;
using testing::TempDir;

const cv::Size kSize(200, 150);

int Count(const std::string& text, const std::string& needle) {
  int count = 0;
  for (size_t at = text.find(needle); at != std::string::npos; at = text.find(needle, at + 1)) {
    ++count;
  }
  return count;
}

// DIR/Glide: a square gliding 3 px right and 1.5 px down a frame, 30 frames: it leaves its
// first box within 8 frames, so a tracker that stands still scores little. DIR/Pair: two
// squares, one ground-truth file each, attributes SV and OCC.
std::string MakeDataset(const TempDir& dir) {
  MakeOtbSequence(dir.File("otb/Glide"), 30, kSize, {{{20, 20}, {3, 1.5}, 24}});
  MakeOtbSequence(dir.File("otb/Pair"), 12, kSize,
                  {{{20, 90}, {2, 0}, 24}, {{150, 20}, {-1, 1}, 20}});
  dir.Write("otb/Pair/attrs.txt", "SV, OCC");
  return dir.File("otb");
}

OtbEvaluationRequest Request(const TempDir& dir, const std::string& out) {
  OtbEvaluationRequest request;
  request.dir = dir.File("otb");
  request.out = dir.File(out);
  request.attend = ResolveTrackerOptions("", {}, "test");  // configs/track.yaml, as attend track
  request.command_line = "test";
  return request;
}

// One evaluation of the three trackers, shared by the tests that read what it wrote.
class EvaluateOtbRun : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = std::make_unique<TempDir>();
    MakeDataset(*dir_);
    results_ = std::make_unique<OtbResults>(EvaluateOtb(Request(*dir_, "report")));
  }
  static void TearDownTestSuite() {
    results_.reset();
    dir_.reset();
  }
  static std::unique_ptr<TempDir> dir_;
  static std::unique_ptr<OtbResults> results_;
};
std::unique_ptr<TempDir> EvaluateOtbRun::dir_;
std::unique_ptr<OtbResults> EvaluateOtbRun::results_;

TEST_F(EvaluateOtbRun, FindsAndNamesTheSequencesAndRunsEveryTracker) {
  ASSERT_EQ(results_->sequences.size(), 3u);
  EXPECT_EQ(results_->sequences[0].name, "Glide");
  EXPECT_EQ(results_->sequences[1].name, "Pair-1");
  EXPECT_EQ(results_->sequences[2].name, "Pair-2");
  EXPECT_EQ(results_->sequences[0].frames, 30);
  EXPECT_EQ(results_->sequences[2].attributes, (std::vector<std::string>{"SV", "OCC"}));
  ASSERT_EQ(results_->trackers.size(), 3u);
  EXPECT_EQ(results_->trackers[0].name, "attend");
  EXPECT_EQ(results_->trackers[0].options["kind"], "bip");
  EXPECT_EQ(results_->trackers[0].options["mode"], "correlation");
  EXPECT_NE(results_->trackers[0].description.find("mode correlation"), std::string::npos);
  EXPECT_EQ(results_->trackers[2].options["lost_frames"], 1000000);
  for (const OtbSequenceResult& sequence : results_->sequences) {
    for (size_t t = 0; t < 3; ++t) {
      const OtbRun& run = sequence.runs[t];
      EXPECT_TRUE(run.started) << sequence.name << " " << results_->trackers[t].name;
      EXPECT_EQ(run.updates + run.lost_frames - (run.lost_frames > 0 ? 1 : 0), sequence.frames - 1);
      EXPECT_GT(run.ms_per_frame, 0.0);
    }
  }
}

TEST_F(EvaluateOtbRun, CsrtFollowsTheGlidingSquareWhereStandingStillFails) {
  const OtbSequenceResult& glide = results_->sequences[0];
  EXPECT_GT(glide.runs[2].scores.success_auc, 0.6);
  EXPECT_GT(glide.runs[2].scores.precision_20, 0.9);
  // A tracker that keeps the first box: its score is far below.
  std::vector<cv::Rect2d> truth, still;
  for (int i = 0; i < 30; ++i) {
    truth.emplace_back(20 + std::lround(3 * i), 20 + std::lround(1.5 * i), 24, 24);
    still.push_back(truth[0]);
  }
  EXPECT_LT(ScoreTracking(still, truth).success_auc, 0.2);
}

TEST_F(EvaluateOtbRun, ResultsJsonHoldsTheCurvesAndThePageTwoPlotsPerGroup) {
  const nlohmann::json json = nlohmann::json::parse(ReadText(dir_->File("report/results.json")));
  ASSERT_EQ(json["sequences"].size(), 3u);
  for (const nlohmann::json& sequence : json["sequences"]) {
    for (const char* tracker : {"attend", "kcf", "csrt"}) {
      EXPECT_EQ(sequence["trackers"][tracker]["success"].size(), 21u);
      EXPECT_EQ(sequence["trackers"][tracker]["precision"].size(), 51u);
    }
  }
  // All sequences, SV and OCC.
  ASSERT_EQ(json["groups"].size(), 3u);
  EXPECT_EQ(json["groups"][1]["attribute"], "SV");
  EXPECT_EQ(json["groups"][0]["trackers"]["csrt"]["success"].size(), 21u);
  EXPECT_DOUBLE_EQ(json["sequences"][0]["trackers"]["csrt"]["success_auc"].get<double>(),
                   results_->sequences[0].runs[2].scores.success_auc);
  EXPECT_EQ(json["trackers"][0]["options"]["mode"], "correlation");
  EXPECT_FALSE(json["cpu"].get<std::string>().empty());
  EXPECT_GT(json["seconds"].get<double>(), 0.0);

  const std::string html = ReadText(dir_->File("report/index.html"));
  EXPECT_EQ(Count(html, "<svg"), 2 * 3);
  EXPECT_EQ(Count(html, "<script"), 0);
  EXPECT_NE(html.find("Success plots of OPE - Scale Variation (2)"), std::string::npos);
}

TEST_F(EvaluateOtbRun, EachTracksFileRescoresToTheSameAuc) {
  for (const OtbSequenceResult& sequence : results_->sequences) {
    for (size_t t = 0; t < results_->trackers.size(); ++t) {
      const OtbRun& run = sequence.runs[t];
      ScoreTracksRequest request;
      request.tracks = dir_->File("report/" + run.tracks);
      request.gt = sequence.ground_truth;
      const nlohmann::json report = ScoreTracks(request);
      ASSERT_EQ(report["targets"].size(), 1u) << run.tracks;
      EXPECT_DOUBLE_EQ(report["targets"][0]["success_auc"].get<double>(), run.scores.success_auc)
          << run.tracks;
      EXPECT_DOUBLE_EQ(report["targets"][0]["precision_20"].get<double>(), run.scores.precision_20)
          << run.tracks;
    }
  }
}

TEST(EvaluateOtb, UnknownOrRepeatedTrackersAndSequencesAreConfigurationErrors) {
  TempDir dir;
  MakeOtbSequence(dir.File("otb/Short"), 3, kSize, {{{20, 20}, {1, 0}, 24}});
  OtbEvaluationRequest request = Request(dir, "report");
  request.trackers = {"kcf", "mosse"};
  const std::string unknown = ErrorOf<ConfigError>([&] { EvaluateOtb(request); });
  EXPECT_NE(unknown.find("unknown tracker 'mosse'"), std::string::npos) << unknown;
  request.trackers = {"kcf", "kcf"};
  EXPECT_NE(ErrorOf<ConfigError>([&] { EvaluateOtb(request); }).find("named twice"),
            std::string::npos);
  request.trackers = {"kcf"};
  request.sequences = {"Shrot"};
  const std::string sequence = ErrorOf<ConfigError>([&] { EvaluateOtb(request); });
  EXPECT_NE(sequence.find("did you mean 'Short'"), std::string::npos) << sequence;
  EXPECT_FALSE(fs::exists(dir.File("report")));
}

TEST(EvaluateOtb, BadInputIsRefusedBeforeTheReportIsWritten) {
  TempDir dir;
  OtbEvaluationRequest request = Request(dir, "report");
  request.trackers = {"kcf"};
  EXPECT_NE(ErrorOf<InputError>([&] { EvaluateOtb(request); }).find("no such folder"),
            std::string::npos);
  fs::create_directories(dir.File("otb/empty"));
  EXPECT_NE(ErrorOf<InputError>([&] { EvaluateOtb(request); }).find("no OTB sequence"),
            std::string::npos);
  MakeOtbSequence(dir.File("otb/Short"), 3, kSize, {{{20, 20}, {1, 0}, 24}});
  dir.Write("otb/Short/groundtruth_rect.txt", "21\t21\t24\t24\n22 21 24\n");
  const std::string line = ErrorOf<InputError>([&] { EvaluateOtb(request); });
  EXPECT_NE(line.find("Short/groundtruth_rect.txt:2"), std::string::npos) << line;
  EXPECT_FALSE(fs::exists(dir.File("report")));
}

TEST(EvaluateOtb, AnUnreadableImageIsNamedAndLeavesNoResults) {
  TempDir dir;
  MakeOtbSequence(dir.File("otb/Short"), 4, kSize, {{{20, 20}, {1, 0}, 24}});
  dir.Write("otb/Short/img/0003.jpg", "not an image");
  OtbEvaluationRequest request = Request(dir, "report");
  request.trackers = {"kcf"};
  const std::string message = ErrorOf<InputError>([&] { EvaluateOtb(request); });
  EXPECT_NE(message.find("Short: frame 2"), std::string::npos) << message;
  EXPECT_NE(message.find("img/0003.jpg"), std::string::npos) << message;
  EXPECT_FALSE(fs::exists(dir.File("report/results.json")));
  EXPECT_FALSE(fs::exists(dir.File("report/index.html")));
}

TEST(EvaluateOtb, AnExistingReportIsReplacedOnlyWithOverwrite) {
  TempDir dir;
  MakeOtbSequence(dir.File("otb/Short"), 3, kSize, {{{20, 20}, {1, 0}, 24}});
  OtbEvaluationRequest request = Request(dir, "report");
  request.trackers = {"kcf"};
  dir.Write("report/mine.txt", "a file of the user's");
  EXPECT_NE(ErrorOf<OutputError>([&] { EvaluateOtb(request); }).find("not empty"),
            std::string::npos);
  request.overwrite = true;
  EXPECT_NE(ErrorOf<OutputError>([&] { EvaluateOtb(request); }).find("previous OTB report"),
            std::string::npos);
  fs::remove(dir.File("report/mine.txt"));
  request.overwrite = false;
  EvaluateOtb(request);
  EXPECT_TRUE(fs::exists(dir.File("report/tracks/kcf/Short.csv")));
  EXPECT_NE(ErrorOf<OutputError>([&] { EvaluateOtb(request); }).find("--overwrite"),
            std::string::npos);
  request.overwrite = true;
  request.trackers = {"csrt"};
  const OtbResults again = EvaluateOtb(request);
  EXPECT_EQ(again.trackers[0].name, "csrt");
  EXPECT_FALSE(fs::exists(dir.File("report/tracks/kcf")));
  EXPECT_TRUE(fs::exists(dir.File("report/results.json")));
}

}  // namespace
}  // namespace attend
