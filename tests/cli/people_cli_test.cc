// configs/people.yaml through the command line (issue 43): without its networks it is a
// configuration error naming the key, the file and where to get it; a network that does not
// fit its decoder is bad input naming the shapes; with the reference data's networks it runs on
// real pedestrian frames, labels its targets as people and reports the detector's cost.
#include <gtest/gtest.h>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "tests/cli/attend_cli.h"
#include "tests/support/attend_process.h"
#include "tests/support/scoped_env.h"
#include "tests/support/temp_dir.h"

namespace attend {
namespace {

namespace fs = std::filesystem;
using testing::Attend;
using testing::Contains;

std::string PeopleConfig() { return testing::ProjectRoot() + "/configs/people.yaml"; }

// ATTEND_MODELS for the runs a test starts.
class ModelsFolder : public testing::ScopedEnv {
 public:
  explicit ModelsFolder(const std::string& folder) : ScopedEnv("ATTEND_MODELS", folder) {}
};

TEST(PeopleCli, WithoutItsNetworksTheConfigurationIsAnErrorNamingKeyFileAndWhereToGetIt) {
  testing::TempDir dir;
  const ModelsFolder models((dir.path() / "no_models").string());
  const testing::Result result =
      Attend(dir, {"run", "--config", PeopleConfig(), "--frames", "0:1", "--out",
                   (dir.path() / "run").string()});
  // The first key read names its network: the appearance's.
  EXPECT_EQ(result.status, 2) << result.err;
  EXPECT_TRUE(Contains(result.err, "people.yaml:")) << result.err;
  EXPECT_TRUE(Contains(result.err, "attention.appearance")) << result.err;
  EXPECT_TRUE(Contains(result.err, "osnet/osnet_x0_25_msmt17.onnx")) << result.err;
  EXPECT_TRUE(Contains(result.err, "docs/MODELS.md")) << result.err;
  EXPECT_TRUE(Contains(result.err, "no_models")) << result.err;  // $ATTEND_MODELS was looked in
  EXPECT_FALSE(fs::exists(dir.path() / "run"));
  // The detector's, with the appearance left out.
  const testing::Result detector =
      Attend(dir, {"run", "--config", PeopleConfig(), "--set", "attention.appearance=''", "--frames",
                   "0:1", "--out", (dir.path() / "run").string()});
  EXPECT_EQ(detector.status, 2) << detector.err;
  EXPECT_TRUE(Contains(detector.err, "people.yaml:")) << detector.err;
  EXPECT_TRUE(Contains(detector.err, "features.1.model")) << detector.err;
  EXPECT_TRUE(Contains(detector.err, "yolox/yolox_nano.onnx")) << detector.err;
  EXPECT_TRUE(Contains(detector.err, "docs/MODELS.md")) << detector.err;
}

TEST(PeopleCli, AMissingAppearanceNetworkIsAnErrorAtItsKey) {
  testing::TempDir dir;
  const std::string config = dir.Write("reid.yaml",
                                       "attention:\n  memory_frames: 10\n"
                                       "  appearance: nowhere/osnet.onnx\n");
  const testing::Result result = Attend(
      dir, {"run", "--config", config, "--frames", "0:1", "--out", (dir.path() / "run").string()});
  EXPECT_EQ(result.status, 2) << result.err;
  EXPECT_TRUE(Contains(result.err, "reid.yaml:3")) << result.err;
  EXPECT_TRUE(Contains(result.err, "attention.appearance")) << result.err;
  EXPECT_TRUE(Contains(result.err, "nowhere/osnet.onnx")) << result.err;
}

// The reference data's networks, or a skip.
std::string SharedModels() {
  const std::string models = testing::SharedData() + "/models";
  return fs::exists(models + "/yolox/yolox_nano.onnx") &&
                 fs::exists(models + "/osnet/osnet_x0_25_msmt17.onnx")
             ? models
             : "";
}

TEST(PeopleCli, ANetworkThatDoesNotFitItsDecoderIsBadInputNamingTheShapes) {
  const std::string models = SharedModels();
  if (models.empty()) GTEST_SKIP() << "no reference networks in " << testing::SharedData();
  testing::TempDir dir;
  const std::string config = dir.Write(
      "faces.yaml", "features:\n  - {name: faces, backend: dnn, decoder: yunet, model: " +
                        models + "/yolox/yolox_nano.onnx}\n");
  const testing::Result result = Attend(
      dir, {"run", "--config", config, "--frames", "0:1", "--out", (dir.path() / "run").string()});
  EXPECT_EQ(result.status, 3) << result.err;
  EXPECT_TRUE(Contains(result.err, "faces.yaml:2")) << result.err;
  EXPECT_TRUE(Contains(result.err, "decoder yunet")) << result.err;
  EXPECT_TRUE(Contains(result.err, "output 1x2100x85")) << result.err;
}

TEST(PeopleCli, OnRealPedestriansTargetsArePeopleAndTheDetectorsCostIsReported) {
  const std::string models = SharedModels();
  const std::string sequence = testing::SharedData() + "/mot/TUD-Stadtmitte";
  if (models.empty() || !fs::exists(sequence)) {
    GTEST_SKIP() << "no reference networks or " << sequence;
  }
  testing::TempDir dir;
  const ModelsFolder folder(models);
  const std::string run = (dir.path() / "run").string();
  const testing::Result result = Attend(dir, {"run", "--config", PeopleConfig(), "--sequence",
                                              sequence, "--frames", "0:9", "--out", run});
  ASSERT_EQ(result.status, 0) << result.err;
  std::ifstream summary_file(run + "/summary.json");
  const nlohmann::json summary = nlohmann::json::parse(summary_file);
  const nlohmann::json& people = summary.at("detectors").at("people");
  // The whole working frame (320 x 240) at YOLOX's 416 px, padded: 416 x 320 a frame.
  EXPECT_DOUBLE_EQ(people.at("searched_pixels").get<double>(), 416.0 * 320.0);
  EXPECT_GT(people.at("ms").get<double>(), 0.0);
  std::ifstream frames(run + "/frames.jsonl");
  std::string line;
  int people_targets = 0, targets = 0;
  while (std::getline(frames, line)) {
    const nlohmann::json record = nlohmann::json::parse(line);
    for (const nlohmann::json& target : record.at("targets")) {
      ++targets;
      if (target.value("label", "") == "person") ++people_targets;
    }
  }
  // TUD-Stadtmitte's first frames hold several walking people: several targets, all people.
  EXPECT_GE(targets, 20);
  EXPECT_EQ(people_targets, targets);
}

}  // namespace
}  // namespace attend
