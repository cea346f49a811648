// attend eval-scanpaths end to end on a dataset written here, whose answers are known by
// construction (docs/FIXATIONS.md, "Scanpaths").
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "io/pfm.h"
#include "tests/cli/attend_cli.h"
#include "tests/support/attend_process.h"
#include "tests/support/temp_dir.h"

namespace attend {
namespace {

using testing::Attend;
using testing::ReadText;
using testing::Result;

// Both observers look first at the centre (the fixation cross), then at these points (1-based
// pixels, as the file stores them), 200 ms each.
const std::vector<cv::Point> kLooks = {{10, 10}, {100, 15}, {90, 70}, {20, 60}};

// data/: two 120 x 80 images, each with two observers who look at the same places in the same
// order; maps/: a scanpath.json that attends those places in that order, and maps.
void WriteDataset(const testing::TempDir& dir) {
  namespace fs = std::filesystem;
  fs::create_directories(dir.File("data/stimuli"));
  fs::create_directories(dir.File("data/fixations"));
  fs::create_directories(dir.File("maps"));
  nlohmann::json scanpaths = nlohmann::json::object();
  for (const std::string id : {"a", "b"}) {
    ASSERT_TRUE(cv::imwrite(dir.File("data/stimuli/" + id + ".png"),
                            cv::Mat(80, 120, CV_8UC3, cv::Scalar(90, 120, 150))));
    std::ofstream fixations(dir.File("data/fixations/" + id + ".txt"));
    fixations << "# subject x y duration_ms\n";
    for (int subject = 0; subject < 2; ++subject) {
      fixations << subject << " 60 40 300\n";
      for (const cv::Point& p : kLooks) fixations << subject << " " << p.x << " " << p.y << " 200\n";
    }
    nlohmann::json path = nlohmann::json::array();
    for (const cv::Point& p : kLooks) path.push_back({{"x", p.x - 1}, {"y", p.y - 1}});
    scanpaths[id] = path;
    cv::Mat map(80, 120, CV_32FC1, cv::Scalar(0.f));
    map.at<float>(9, 9) = 1.f;
    map.at<float>(69, 89) = 0.5f;
    WritePfm(dir.File("maps/" + id + ".pfm"), map);
  }
  std::ofstream(dir.File("maps/scanpath.json")) << scanpaths.dump(2);
}

double Mean(const nlohmann::json& methods, const std::string& method, const std::string& measure) {
  return methods.at(method).at(measure).at("mean").get<double>();
}

const std::vector<std::string> kMeasures = {"scanmatch",    "sequence",    "mm_shape",
                                            "mm_direction", "mm_length",   "mm_position",
                                            "mm_duration"};

TEST(EvalScanpathsCli, IdenticalObserversAndAMatchingModelScoreOne) {
  testing::TempDir dir;
  WriteDataset(dir);
  const Result r = Attend(dir, {"eval-scanpaths", "attend=maps", "--dataset", "data",
                                "--baselines", "human", "centre", "peaks", "--out", "scores",
                                "--quiet"});
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json report = nlohmann::json::parse(ReadText(dir.File("scores/scanpaths.json")));
  const nlohmann::json& methods = report.at("methods");
  for (const std::string& measure : kMeasures) {
    EXPECT_NEAR(Mean(methods, "human", measure), 1.0, 1e-9) << measure;
    EXPECT_NEAR(Mean(methods, "attend", measure), 1.0, 1e-9) << measure;
  }
  EXPECT_EQ(methods.at("human").at("scanmatch").at("n").get<int>(), 2);
  // The centre draws and the two peaks (the map's two bright pixels) are scored, below 1.
  EXPECT_LT(Mean(methods, "centre", "scanmatch"), 1.0);
  EXPECT_EQ(methods.at("attend_peaks").at("scanmatch").at("n").get<int>(), 2);
  EXPECT_LT(Mean(methods, "attend_peaks", "sequence"), 1.0);
  // The models last the observers' median duration, 200 ms (the dropped first is 300 ms).
  EXPECT_DOUBLE_EQ(report.at("options").at("model_duration_s").get<double>(), 0.2);
  EXPECT_TRUE(report.at("options").at("drop_first").get<bool>());
  EXPECT_TRUE(std::filesystem::exists(dir.File("scores/attend.csv")));
  EXPECT_TRUE(std::filesystem::exists(dir.File("scores/human.csv")));
  EXPECT_NE(r.out.find("| attend | 2 | 1.000 +- 0.000 |"), std::string::npos) << r.out;
}

TEST(EvalScanpathsCli, KeepingTheFirstFixationComparesItToo) {
  testing::TempDir dir;
  WriteDataset(dir);
  const Result r = Attend(dir, {"eval-scanpaths", "maps", "--dataset", "data", "--keep-first",
                                "--length", "3", "--out", "s", "--quiet"});
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json report = nlohmann::json::parse(ReadText(dir.File("s/scanpaths.json")));
  // The observers' first three are the centre and two looks; the model's, three looks.
  EXPECT_LT(Mean(report.at("methods"), "maps", "sequence"), 0.99);
  EXPECT_FALSE(report.at("options").at("drop_first").get<bool>());
}

TEST(EvalScanpathsCli, BadInputIsExitThreeNamingTheFile) {
  testing::TempDir dir;
  WriteDataset(dir);
  // The image missing from scanpath.json.
  nlohmann::json scanpaths = nlohmann::json::parse(ReadText(dir.File("maps/scanpath.json")));
  scanpaths.erase("b");
  std::ofstream(dir.File("maps/scanpath.json")) << scanpaths.dump();
  Result r = Attend(dir, {"eval-scanpaths", "maps", "--dataset", "data", "--quiet"});
  EXPECT_EQ(r.status, 3);
  EXPECT_NE(r.err.find("scanpath.json: no scanpath for image b"), std::string::npos) << r.err;
  // An empty scanpath.
  scanpaths["b"] = nlohmann::json::array();
  std::ofstream(dir.File("maps/scanpath.json")) << scanpaths.dump();
  r = Attend(dir, {"eval-scanpaths", "maps", "--dataset", "data", "--quiet"});
  EXPECT_EQ(r.status, 3);
  EXPECT_NE(r.err.find("image b: empty scanpath"), std::string::npos) << r.err;
  // Scored 0 when asked.
  r = Attend(dir, {"eval-scanpaths", "maps", "--dataset", "data", "--quiet", "--empty-scanpath",
                   "zero", "--out", "zero"});
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json zero = nlohmann::json::parse(ReadText(dir.File("zero/scanpaths.json")));
  EXPECT_EQ(zero.at("methods").at("maps").at("empty_scanpaths").get<int>(), 1);
  EXPECT_NEAR(Mean(zero.at("methods"), "maps", "scanmatch"), 0.5, 1e-9);  // image a: 1, b: 0
  // No scanpath.json at all.
  std::filesystem::remove(dir.File("maps/scanpath.json"));
  r = Attend(dir, {"eval-scanpaths", "maps", "--dataset", "data", "--quiet"});
  EXPECT_EQ(r.status, 3);
  EXPECT_NE(r.err.find("scanpath.json: missing"), std::string::npos) << r.err;
  // A bad fixation line: named with its line.
  {
    std::ofstream bad(dir.File("data/fixations/a.txt"), std::ios::app);
    bad << "1 12 x 200\n";
  }
  r = Attend(dir, {"eval-scanpaths", "--dataset", "data", "--baselines", "human", "--quiet"});
  EXPECT_EQ(r.status, 3);
  EXPECT_NE(r.err.find("a.txt:12"), std::string::npos) << r.err;
}

TEST(EvalScanpathsCli, BadFlagsAreExitTwo) {
  testing::TempDir dir;
  WriteDataset(dir);
  for (const std::vector<std::string>& args :
       std::vector<std::vector<std::string>>{{"--grid", "12by8"},
                                             {"--baselines", "middle"},
                                             {"--duration-column", "2"},
                                             {"--length", "0"},
                                             {"--no-such-flag"}}) {
    std::vector<std::string> command = {"eval-scanpaths", "maps", "--dataset", "data", "--quiet"};
    command.insert(command.end(), args.begin(), args.end());
    const Result r = Attend(dir, command);
    EXPECT_EQ(r.status, 2) << args[0] << ": " << r.err;
  }
  // Temporal bins without durations in the files.
  const Result r = Attend(dir, {"eval-scanpaths", "maps", "--dataset", "data", "--quiet",
                                "--duration-column", "none", "--scanmatch-bin-ms", "50"});
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("no durations"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace attend
