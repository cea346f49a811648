// Comparing runs (eval/run_comparison.h): the saliency metrics against values worked out
// by hand, the flattened configuration and its differences, and CompareRuns on run folders
// written here (a run against its own copy, against a changed run, with missing maps).
#include "eval/run_comparison.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "io/pfm.h"
#include "eval/run_report.h"
#include "tests/support/temp_dir.h"
#include "util/error.h"

namespace fs = std::filesystem;

namespace attend {
namespace {

using testing::TempDir;

cv::Mat Map2x2(float a, float b, float c, float d) { return (cv::Mat_<float>(2, 2) << a, b, c, d); }

TEST(SaliencyMetrics, HandWorkedValues) {
  // P = [1 0; 0 1], Q = [2 1; 0 1].
  // CC: deviations (.5 -.5 -.5 .5) and (1 0 -1 0); cov = .25, sigma_P = .5,
  //     sigma_Q = sqrt(.5), CC = .25 / (.5 sqrt(.5)) = 1 / sqrt(2).
  // SIM: P/sum = (.5 0 0 .5), Q/sum = (.5 .25 0 .25), sum of minima = .5 + .25 = .75.
  // KL: .5 log(1) + .25 log(.25 / eps) + 0 + .25 log(.25 / .5).
  const cv::Mat p = Map2x2(1, 0, 0, 1), q = Map2x2(2, 1, 0, 1);
  EXPECT_NEAR(CorrelationCoefficient(p, q), 1.0 / std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(Similarity(p, q), 0.75, 1e-12);
  const double kl = 0.25 * std::log(0.25 / kSaliencyEpsilon) + 0.25 * std::log(0.5);
  EXPECT_NEAR(KlDivergence(p, q), kl, 1e-9);
  EXPECT_NEAR(kl, 8.491, 1e-3);
  // KL is not symmetric: with the roles swapped the terms are .5 log(.5 / .5), 0 (no mass),
  // 0 and .5 log(.5 / .25), so .5 log 2.
  EXPECT_NEAR(KlDivergence(q, p), 0.5 * std::log(2.0), 1e-9);
}

TEST(SaliencyMetrics, IdenticalAndOppositeMaps) {
  cv::Mat p(12, 16, CV_32F);
  cv::RNG(7).fill(p, cv::RNG::UNIFORM, 0.0, 1.0);
  const SaliencyMetrics same = CompareSaliency(p, p.clone());
  EXPECT_NEAR(same.cc, 1.0, 1e-12);
  EXPECT_NEAR(same.sim, 1.0, 1e-12);
  EXPECT_NEAR(same.kl, 0.0, 1e-12);
  // Scaling a map changes none of them: all normalise (up to the float rounding of 3p).
  const SaliencyMetrics scaled = CompareSaliency(p, p * 3.0);
  EXPECT_NEAR(scaled.cc, 1.0, 1e-6);
  EXPECT_NEAR(scaled.sim, 1.0, 1e-6);
  EXPECT_NEAR(scaled.kl, 0.0, 1e-6);
  // Disjoint maps [1 0; 0 0] and [0 1; 0 0]: CC -1/3, from the deviations (.75 -.25 -.25 -.25) and
  // (-.25 .75 -.25 -.25), cov = -1/16, sigma^2 = 3/16.
  const cv::Mat a = Map2x2(1, 0, 0, 0), b = Map2x2(0, 1, 0, 0);
  EXPECT_NEAR(CorrelationCoefficient(a, b), -1.0 / 3.0, 1e-12);
  EXPECT_NEAR(Similarity(a, b), 0.0, 1e-12);
  EXPECT_NEAR(KlDivergence(a, b), std::log(1.0 / kSaliencyEpsilon), 1e-6);
}

TEST(SaliencyMetrics, UndefinedOnFlatOrEmptyMaps) {
  const cv::Mat flat = Map2x2(0.5f, 0.5f, 0.5f, 0.5f), zero = Map2x2(0, 0, 0, 0);
  const cv::Mat p = Map2x2(1, 0, 0, 1);
  EXPECT_TRUE(std::isnan(CorrelationCoefficient(flat, p)));
  EXPECT_NEAR(Similarity(flat, p), 0.5, 1e-12);
  EXPECT_TRUE(std::isnan(Similarity(zero, p)));
  EXPECT_TRUE(std::isnan(KlDivergence(p, zero)));
  EXPECT_THROW(CorrelationCoefficient(p, cv::Mat::zeros(3, 3, CV_32F)), InternalError);
}

TEST(ConfigDiff, FlattensByNameAndFindsTheKeysThatDiffer) {
  const FlatConfig a = FlattenConfigText(
      "sequence: {width: 320, folder: \"\"}\n"
      "output: {dump: [overlay, saliency]}\n"
      "features:\n"
      "  - {name: skin, weight: 1.0, model: m.yaml}\n"
      "  - {name: disparity, weight: 1.0}\n"
      "plugins: []\n");
  EXPECT_EQ(a.at("features.skin.weight"), "1.0");
  EXPECT_EQ(a.at("features.skin.model"), "m.yaml");
  EXPECT_EQ(a.at("output.dump"), "[overlay, saliency]");
  EXPECT_EQ(a.at("sequence.width"), "320");
  EXPECT_EQ(a.count("features.skin.name"), 0u);
  EXPECT_TRUE(DiffConfigs(a, a).empty());

  const FlatConfig b = FlattenConfigText(
      "sequence: {width: 320.0, folder: \"\"}\n"
      "output: {dump: [overlay, saliency]}\n"
      "features:\n"
      "  - {name: skin, weight: 0.5, model: m.yaml}\n"
      "  - {name: disparity, weight: 1, extra: 3}\n"
      "plugins: []\n");
  const std::vector<ConfigDifference> diff = DiffConfigs(a, b);
  ASSERT_EQ(diff.size(), 2u);
  EXPECT_EQ(diff[0].key, "features.disparity.extra");
  EXPECT_FALSE(diff[0].a.has_value());
  EXPECT_EQ(diff[0].b.value(), "3");
  EXPECT_EQ(diff[1].key, "features.skin.weight");
  EXPECT_EQ(diff[1].a.value(), "1.0");
  EXPECT_EQ(diff[1].b.value(), "0.5");
}

TEST(ConfigDiff, UnreadableConfigIsAnInputError) {
  const TempDir dir;
  const std::string path = dir.Write("config.yaml", "a: [1, 2\n");
  try {
    FlattenConfigFile(path);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
}

TargetRecord Target(int id, cv::Rect box, TargetState state) {
  TargetRecord t;
  t.id = id;
  t.bbox = box;
  t.area = box.area();
  t.state = state;
  return t;
}

// A run folder of `frames` frames: target 1 from frame 0 at a fixed box, target 2 from frame 1
// at `second_box`; a saliency map per frame (unless `maps` is false) with a bright blob.
void WriteRun(const fs::path& dir, int frames, const std::string& config, cv::Rect second_box,
              bool maps, double blob_shift = 0.0) {
  fs::create_directories(dir / "saliency");
  std::ofstream(dir / "config.yaml") << config;
  std::ofstream(dir / "summary.json")
      << "{\"frames\": " << frames << ", \"interrupted\": false, \"sequence\": {\"name\": "
      << "\"lab\"}}\n";
  std::ofstream lines(dir / "frames.jsonl");
  for (int f = 0; f < frames; ++f) {
    FrameRecord record;
    record.frame = f;
    record.targets.push_back(
        Target(1, {10, 10, 20, 20}, f == 0 ? TargetState::kNew : TargetState::kTracked));
    if (f == 0) record.new_ids.push_back(1);
    if (f >= 1) {
      record.targets.push_back(
          Target(2, second_box, f == 1 ? TargetState::kNew : TargetState::kTracked));
      if (f == 1) record.new_ids.push_back(2);
    }
    record.timings.Add("read", 1.0 + f);
    record.timings.Add("saliency", 2.0);
    lines << FrameRecordToJson(record) << "\n";
    if (maps) {
      cv::Mat map(24, 32, CV_32F);
      for (int y = 0; y < map.rows; ++y) {
        for (int x = 0; x < map.cols; ++x) {
          const double dx = x - 10 - f - blob_shift, dy = y - 12;
          map.at<float>(y, x) = static_cast<float>(std::exp(-(dx * dx + dy * dy) / 20.0));
        }
      }
      WritePfm(DumpPath(dir.string(), "saliency", f, "pfm"), map);
    }
  }
}

const char* kConfig = "features:\n  - {name: skin, weight: 1.0}\nselect: {max_new: 2}\n";

TEST(CompareRuns, RunAgainstItsCopyIsPerfect) {
  const TempDir dir;
  WriteRun(dir.path() / "a", 4, kConfig, {50, 10, 20, 20}, true);
  fs::copy(dir.path() / "a", dir.path() / "copy", fs::copy_options::recursive);
  const RunComparison c = CompareRuns(LoadRun(dir.File("a")), LoadRun(dir.File("copy")));
  EXPECT_TRUE(c.config.empty());
  EXPECT_TRUE(c.notes.empty()) << c.notes.front();
  ASSERT_EQ(c.frames.size(), 4u);
  for (const FrameComparison& f : c.frames) {
    ASSERT_TRUE(f.saliency.has_value());
    EXPECT_NEAR(f.saliency->cc, 1.0, 1e-9);
    EXPECT_NEAR(f.saliency->sim, 1.0, 1e-9);
    EXPECT_NEAR(f.saliency->kl, 0.0, 1e-9);
    EXPECT_EQ(f.matched, f.targets_a);
  }
  ASSERT_EQ(c.matches.size(), 2u);
  EXPECT_EQ(c.matches[0].id_a, 1);
  EXPECT_EQ(c.matches[0].id_b, 1);
  EXPECT_EQ(c.matches[0].frames_matched, 4);
  EXPECT_EQ(c.matches[1].id_a, 2);
  EXPECT_EQ(c.matches[1].id_b, 2);
  EXPECT_TRUE(c.same_order);
  ASSERT_EQ(c.timings.size(), 2u);
  EXPECT_EQ(c.timings[0].stage, "read");
  EXPECT_NEAR(c.timings[0].a.value(), 2.5, 1e-12);  // (1 + 2 + 3 + 4) / 4
  EXPECT_NEAR(c.timings[0].b.value(), 2.5, 1e-12);
  const nlohmann::ordered_json json = ComparisonToJson(c);
  EXPECT_EQ(json["targets"]["only_a"].size(), 0u);
  EXPECT_EQ(json["targets"]["only_b"].size(), 0u);
  EXPECT_EQ(json["config_differences"].size(), 0u);
}

TEST(CompareRuns, ChangedRunShowsItsDifferences) {
  const TempDir dir;
  WriteRun(dir.path() / "a", 4, kConfig, {50, 10, 20, 20}, true);
  // Target 2 far away (IoU 0), one frame fewer, one weight changed, the blob moved.
  WriteRun(dir.path() / "b", 3, "features:\n  - {name: skin, weight: 0.25}\nselect: {max_new: 2}\n",
           {90, 40, 20, 20}, true, 3.0);
  const RunComparison c = CompareRuns(LoadRun(dir.File("a")), LoadRun(dir.File("b")));
  ASSERT_EQ(c.config.size(), 1u);
  EXPECT_EQ(c.config[0].key, "features.skin.weight");
  ASSERT_EQ(c.frames.size(), 3u);
  ASSERT_EQ(c.notes.size(), 1u);
  EXPECT_NE(c.notes[0].find("3 common frames"), std::string::npos) << c.notes[0];
  for (const FrameComparison& f : c.frames) {
    ASSERT_TRUE(f.saliency.has_value());
    EXPECT_LT(f.saliency->cc, 0.9);
    EXPECT_GT(f.saliency->kl, 0.1);
  }
  int matched = 0, only_a = 0, only_b = 0;
  for (const TargetMatch& m : c.matches) {
    if (m.id_a >= 0 && m.id_b >= 0) {
      ++matched;
    } else if (m.id_a >= 0) {
      EXPECT_EQ(m.id_a, 2);
      ++only_a;
    } else {
      EXPECT_EQ(m.id_b, 2);
      ++only_b;
    }
  }
  EXPECT_EQ(matched, 1);
  EXPECT_EQ(only_a, 1);
  EXPECT_EQ(only_b, 1);
  EXPECT_EQ(MostDifferentFrames(c, 1).size(), 1u);
}

TEST(CompareRuns, MissingMapsAreANoteNotAnError) {
  const TempDir dir;
  WriteRun(dir.path() / "a", 2, kConfig, {50, 10, 20, 20}, true);
  WriteRun(dir.path() / "b", 2, kConfig, {50, 10, 20, 20}, false);
  const RunComparison c = CompareRuns(LoadRun(dir.File("a")), LoadRun(dir.File("b")));
  ASSERT_EQ(c.frames.size(), 2u);
  EXPECT_FALSE(c.frames[0].saliency.has_value());
  EXPECT_FALSE(c.mean_saliency.has_value());
  ASSERT_EQ(c.notes.size(), 1u);
  EXPECT_NE(c.notes[0].find("lack a saliency map"), std::string::npos) << c.notes[0];
  EXPECT_TRUE(ComparisonToJson(c)["frames"][0]["cc"].is_null());
}

TEST(CompareRuns, FolderWithoutFramesIsAnInputErrorNamingIt) {
  const TempDir dir;
  fs::create_directories(dir.path() / "empty");
  try {
    LoadRun(dir.File("empty"));
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(dir.File("empty")), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("frames.jsonl"), std::string::npos) << e.what();
  }
}

TEST(RunReport, Base64) {
  EXPECT_EQ(Base64({}), "");
  EXPECT_EQ(Base64({'f'}), "Zg==");
  EXPECT_EQ(Base64({'f', 'o'}), "Zm8=");
  EXPECT_EQ(Base64({'f', 'o', 'o'}), "Zm9v");
  EXPECT_EQ(Base64({'f', 'o', 'o', 'b', 'a', 'r'}), "Zm9vYmFy");
}

TEST(RunReport, WithoutChartJsTheTablesStayAndTheReportSaysSo) {
  const TempDir dir;
  WriteRun(dir.path() / "a", 3, kConfig, {50, 10, 20, 20}, true);
  WriteRun(dir.path() / "b", 3, "features:\n  - {name: skin, weight: 0.25}\nselect: {max_new: 2}\n",
           {50, 10, 20, 20}, true, 2.0);
  ReportInput input;
  input.runs = {LoadRun(dir.File("a")), LoadRun(dir.File("b"))};
  input.comparisons = {CompareRuns(input.runs[0], input.runs[1])};
  input.chart.path = "looked for nothing";
  const std::string html = ReportHtml(input);
  EXPECT_NE(html.find("Chart.js was not found"), std::string::npos);
  EXPECT_NE(html.find("features.skin.weight"), std::string::npos);
  EXPECT_EQ(html.find("<canvas"), std::string::npos);
  EXPECT_NE(html.find("data:image/png;base64,"), std::string::npos);  // saliency thumbnails
}

}  // namespace
}  // namespace attend
