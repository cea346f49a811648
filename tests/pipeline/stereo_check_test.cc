// `attend run`'s row check of its first stereo frame and summary.json's `stereo` block
// (pipeline/stereo_check.h), on pairs whose rows are known by construction.
#include "pipeline/stereo_check.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "pipeline/run.h"
#include "tests/support/error_message.h"
#include "tests/support/stereo_pair_maker.h"
#include "tests/support/temp_dir.h"

namespace fs = std::filesystem;

namespace attend {
namespace {

// SEQ with two frames of the pair (left, right), at 640x480.
std::string WritePair(const testing::TempDir& dir, const cv::Mat& left, const cv::Mat& right) {
  const fs::path seq = dir.path() / "seq";
  fs::create_directories(seq / "left");
  fs::create_directories(seq / "right");
  for (const char* name : {"000000.png", "000001.png"}) {
    cv::imwrite((seq / "left" / name).string(), left);
    cv::imwrite((seq / "right" / name).string(), right);
  }
  return seq.string();
}

RunRequest PairRequest(const testing::TempDir& dir, const std::string& seq) {
  RunRequest request;
  request.home = testing::ProjectRoot();
  request.options.sequence.source.folder = seq;
  request.out_dir = dir.File("run");
  return request;
}

nlohmann::json Summary(const testing::TempDir& dir) {
  std::ifstream in(dir.File("run/summary.json"));
  return nlohmann::json::parse(in);
}

TEST(StereoCheck, RectifiedPairPassesAndIsRecorded) {
  const testing::TempDir dir;
  const testing::KnownPair pair = testing::MakeKnownPair({640, 480}, 12.0);
  const std::string seq = WritePair(dir, pair.rectified_left, pair.rectified_right);
  const RunSummary summary = RunSequence(PairRequest(dir, seq));
  EXPECT_EQ(summary.frames, 2);  // the frame checked is run too
  const nlohmann::json stereo = Summary(dir)["stereo"];
  EXPECT_TRUE(stereo["calibration"].is_null());
  EXPECT_EQ(stereo["rectified_on_the_fly"], false);
  EXPECT_EQ(stereo["row_check"], true);
  EXPECT_EQ(stereo["row_check_frame"], 0);
  EXPECT_LT(stereo["row_offset_px"].get<double>(), 0.5);
  EXPECT_GE(stereo["matches"].get<int>(), 20);
}

TEST(StereoCheck, ShiftedOrTurnedRightViewIsRefusedNamingTheFrame) {
  const testing::KnownPair pair = testing::MakeKnownPair({640, 480}, 12.0);
  for (const cv::Mat& right :
       {testing::ShiftDown(pair.rectified_right, 3.0), testing::Rotate(pair.rectified_right, 1.0)}) {
    const testing::TempDir dir;
    const std::string seq = WritePair(dir, pair.rectified_left, right);
    const std::string error = testing::InputErrorOf([&] { RunSequence(PairRequest(dir, seq)); });
    EXPECT_NE(error.find("frame 0 ("), std::string::npos) << error;
    EXPECT_NE(error.find("left/000000.png"), std::string::npos) << error;
    EXPECT_NE(error.find("rows do not match"), std::string::npos) << error;
    EXPECT_NE(error.find("attend calibrate"), std::string::npos) << error;
    EXPECT_NE(error.find("--calib"), std::string::npos) << error;
    EXPECT_FALSE(fs::exists(dir.File("run"))) << "refused before the run folder";
  }
}

TEST(StereoCheck, CheckRowsOffRunsAnyPair) {
  const testing::TempDir dir;
  const testing::KnownPair pair = testing::MakeKnownPair({640, 480}, 12.0);
  const std::string seq = WritePair(dir, pair.raw_left, pair.raw_right);
  RunRequest request = PairRequest(dir, seq);
  request.options.sequence.check_rows = false;
  EXPECT_EQ(RunSequence(request).frames, 2);
  const nlohmann::json stereo = Summary(dir)["stereo"];
  EXPECT_EQ(stereo["row_check"], false);
  EXPECT_TRUE(stereo["row_offset_px"].is_null());
}

// The raw pair of a known calibration, given with its calibration: rectified on the fly.
TEST(StereoCheck, FullCalibrationRectifiesARawPair) {
  const testing::TempDir dir;
  const testing::KnownPair pair = testing::MakeKnownPair({640, 480}, 12.0);
  const std::string seq = WritePair(dir, pair.raw_left, pair.raw_right);
  // Without it, the raw pair is refused.
  EXPECT_NE(testing::InputErrorOf([&] { RunSequence(PairRequest(dir, seq)); })
                .find("The pair is not rectified"),
            std::string::npos);
  WriteStereoCalibration(pair.calibration, dir.File("calib.yaml"));
  RunRequest request = PairRequest(dir, seq);
  request.options.sequence.source.calib = dir.File("calib.yaml");
  RunSequence(request);
  const nlohmann::json stereo = Summary(dir)["stereo"];
  EXPECT_EQ(stereo["calibration"]["form"], "full");
  EXPECT_EQ(stereo["calibration"]["source"], dir.File("calib.yaml"));
  EXPECT_EQ(stereo["rectified_on_the_fly"], true);
  EXPECT_LT(stereo["row_offset_px"].get<double>(), 1.0);
}

}  // namespace
}  // namespace attend
