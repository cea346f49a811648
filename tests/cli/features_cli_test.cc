// attend run with feature plugins end to end: the dumped feature and saliency maps, the
// example out-of-tree plugin, and the exit statuses of plugin errors (SPEC 2.3, 3.3, 3.4).
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>

#include "io/ground_truth.h"
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

const char kAllDumps[] = "output.dump=[overlay, regions, features, saliency]";

// Renders the first `frames` frames of the bundled lab scene into dir/seq.
void RenderLab(const testing::TempDir& dir, int frames) {
  const Result r = Attend(dir, {"synth", testing::ProjectRoot() + "/sequences/lab.yaml", "--out",
                                "seq", "--frames", std::to_string(frames)});
  ASSERT_EQ(r.status, 0) << r.err;
}

cv::Mat Map(const testing::TempDir& dir, const std::string& run, const std::string& kind,
            int frame) {
  std::ostringstream name;
  name << run << "/" << kind << "/" << std::setw(6) << std::setfill('0') << frame << ".pfm";
  return ReadPfm(dir.File(name.str()));
}

cv::Rect GroundTruthBox(const testing::TempDir& dir, int frame, int id) {
  for (const GtObject& object : ReadObjectsCsv(dir.File("seq/gt/objects.csv"))) {
    if (object.frame == frame && object.id == id) return cv::Rect(object.box);
  }
  ADD_FAILURE() << "no object " << id << " in frame " << frame;
  return {};
}

std::vector<nlohmann::json> Frames(const testing::TempDir& dir, const std::string& run) {
  std::vector<nlohmann::json> frames;
  std::istringstream lines(ReadText(dir.File(run + "/frames.jsonl")));
  for (std::string line; std::getline(lines, line);) frames.push_back(nlohmann::json::parse(line));
  return frames;
}

TEST(FeaturesCli, RunDumpsFeatureAndSaliencyMapsThatLightUpTheRightObjects) {
  testing::TempDir dir;
  RenderLab(dir, 2);
  const Result r =
      Attend(dir, {"run", "--sequence", "seq", "--out", "run", "--quiet", "--set", kAllDumps});
  ASSERT_EQ(r.status, 0) << r.err;
  for (const std::string kind :
       {"features/colour_contrast", "features/intensity_contrast", "features/skin", "saliency"}) {
    for (const std::string ext : {".pfm", ".png"}) {
      EXPECT_TRUE(fs::exists(dir.File("run/" + kind + "/000001" + ext))) << kind << ext;
    }
  }
  EXPECT_TRUE(fs::exists(dir.File("run/regions/000000.png")));

  // The face (id 7) lights up the skin map; the saturated red box (id 1) stands out in colour
  // contrast against the grey wall.
  const cv::Mat skin = Map(dir, "run", "features/skin", 1);
  const cv::Rect face = GroundTruthBox(dir, 1, 7);
  const cv::Rect face_core(face.x + face.width / 4, face.y + face.height / 4, face.width / 2,
                           face.height / 2);
  EXPECT_GT(cv::mean(skin(face_core))[0], 0.9);
  EXPECT_LT(cv::mean(skin(cv::Rect(0, 0, 60, 40)))[0], 0.05);  // wall, top left
  const cv::Mat colour = Map(dir, "run", "features/colour_contrast", 1);
  const cv::Rect box = GroundTruthBox(dir, 1, 1);
  EXPECT_GT(cv::mean(colour(box))[0], 4 * cv::mean(colour(cv::Rect(0, 0, 60, 40)))[0]);

  // Disparity: the person (shirt, id 6, at 1.9 m) is nearer than the wall (6 m).
  const cv::Mat disparity = Map(dir, "run", "features/disparity", 1);
  const cv::Rect shirt = GroundTruthBox(dir, 1, 6);
  const cv::Rect shirt_core(shirt.x + shirt.width / 4, shirt.y + shirt.height / 4, shirt.width / 2,
                            shirt.height / 2);
  EXPECT_GT(cv::mean(disparity(shirt_core))[0],
            2 * cv::mean(disparity(cv::Rect(20, 0, 60, 40)))[0]);

  // Saliency is the weight-averaged min-max normalisation of the dumped maps (all weights 1).
  cv::Mat expected(skin.size(), CV_32FC1, cv::Scalar(0.f));
  for (const std::string name : {"colour_contrast", "intensity_contrast", "skin", "disparity"}) {
    cv::Mat map = Map(dir, "run", "features/" + name, 1), unit;
    cv::normalize(map, unit, 0.0, 1.0, cv::NORM_MINMAX);
    expected += unit / 4.f;
  }
  EXPECT_LT(cv::norm(expected, Map(dir, "run", "saliency", 1), cv::NORM_INF), 1e-5);

  const std::vector<nlohmann::json> frames = Frames(dir, "run");
  ASSERT_EQ(frames.size(), 2u);
  for (const std::string stage : {"segment", "features", "feature.skin", "feature.colour_contrast",
                                  "feature.disparity", "saliency"}) {
    EXPECT_TRUE(frames[1]["timings_ms"].contains(stage)) << stage;
  }
}

TEST(FeaturesCli, DisabledFeatureLeavesNoTraceAndThreadsDoNotChangeResults) {
  testing::TempDir dir;
  RenderLab(dir, 2);
  Result r = Attend(dir, {"run", "--sequence", "seq", "--out", "a", "--quiet", "--set", kAllDumps,
                          "--set", "features.skin.enabled=false", "--set", "threads=1"});
  ASSERT_EQ(r.status, 0) << r.err;
  r = Attend(dir, {"run", "--sequence", "seq", "--out", "b", "--quiet", "--set", kAllDumps, "--set",
                   "features=[{name: colour_contrast}, {name: intensity_contrast}, "
                   "{name: disparity, smoothness: hard, window: 7, median: 0}]",
                   "--set", "threads=2"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_FALSE(fs::exists(dir.File("a/features/skin")));
  EXPECT_FALSE(Frames(dir, "a")[0]["timings_ms"].contains("feature.skin"));
  for (int frame = 0; frame < 2; ++frame) {
    EXPECT_EQ(
        cv::norm(Map(dir, "a", "saliency", frame), Map(dir, "b", "saliency", frame), cv::NORM_INF),
        0.0);
  }
}

TEST(FeaturesCli, ExamplePluginLoadsFromItsLibraryAndContributes) {
  testing::TempDir dir;
  RenderLab(dir, 3);
  const Result r = Attend(
      dir,
      {"run", "--sequence", "seq", "--out", "run", "--quiet", "--set", kAllDumps, "--set",
       std::string("plugins=[") + EXAMPLE_PLUGIN + "]", "--set",
       "features=[{name: temporal_change, weight: 2, window: 3}, {name: intensity_contrast}]"});
  ASSERT_EQ(r.status, 0) << r.err;
  // Frame 0 has nothing to compare with; the rolling ball (id 2) changes the image later.
  EXPECT_EQ(cv::countNonZero(Map(dir, "run", "features/temporal_change", 0)), 0);
  const cv::Mat change = Map(dir, "run", "features/temporal_change", 2);
  const cv::Rect ball = GroundTruthBox(dir, 2, 2);
  EXPECT_GT(cv::mean(change(ball))[0], 5 * cv::mean(change)[0]);
  // Its weight counts: saliency = (2 N(change) + N(intensity)) / 3.
  cv::Mat a, b;
  cv::normalize(change, a, 0.0, 1.0, cv::NORM_MINMAX);
  cv::normalize(Map(dir, "run", "features/intensity_contrast", 2), b, 0.0, 1.0, cv::NORM_MINMAX);
  const cv::Mat expected = (2.f * a + b) / 3.f;
  EXPECT_LT(cv::norm(expected, Map(dir, "run", "saliency", 2), cv::NORM_INF), 1e-5);
  EXPECT_TRUE(Contains(ReadText(dir.File("run/config.yaml")), "temporal_change"));
}

TEST(FeaturesCli, PluginErrorsExitTwoNamingTheFile) {
  testing::TempDir dir;
  testing::MakeFolderSequence(dir.File("seq"), 2, 32, 24);
  struct Case {
    std::string plugin;
    std::string message;
  };
  const std::vector<Case> cases = {
      {dir.File("missing.so"), "no such file"},
      {ABI_MISMATCH_PLUGIN, "ABI version 99"},
      {NO_ENTRY_PLUGIN, "no 'attend_plugin' entry point"},
      {NAME_CLASH_PLUGIN, "registers feature 'skin', which built-in already registered"},
      {dir.Write("not_a_library.so", "text"), "is not a shared library"},
      // A whole ELF file that the dynamic loader still refuses (a position-independent
      // executable, ET_DYN like a library).
      {"/bin/true", "cannot be loaded"},
  };
  for (const Case& c : cases) {
    const Result r = Attend(
        dir, {"run", "--sequence", "seq", "--out", "run", "--set", "plugins=[" + c.plugin + "]"});
    EXPECT_EQ(r.status, 2) << c.plugin << ": " << r.err;
    EXPECT_TRUE(Contains(r.err, c.plugin)) << r.err;
    EXPECT_TRUE(Contains(r.err, c.message)) << r.err;
    EXPECT_FALSE(fs::exists(dir.File("run"))) << c.plugin;
  }
  // A plugin's feature without its library, and a bad parameter of the example plugin.
  Result r = Attend(dir, {"run", "--sequence", "seq", "--out", "run", "--set",
                          "features=[{name: temporal_change}]"});
  EXPECT_EQ(r.status, 2);
  EXPECT_TRUE(Contains(r.err, "unknown feature 'temporal_change'")) << r.err;
  r = Attend(dir, {"run", "--sequence", "seq", "--out", "run", "--set",
                   std::string("plugins=[") + EXAMPLE_PLUGIN + "]", "--set",
                   "features=[{name: temporal_change, window: 4}]"});
  EXPECT_EQ(r.status, 2);
  EXPECT_TRUE(Contains(r.err, "features.0.window")) << r.err;
}

}  // namespace
}  // namespace attend
