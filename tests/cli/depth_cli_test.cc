// Each target's disparity in a stereo run end to end (issue 44): `attend run` on a rendered
// lab scene records disparity_px close to the scene's exact disparities, `attend eval` scores
// them, a monocular run of the same frames has none, and `attend disparity --regions` needs
// ground truth.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "tests/cli/attend_cli.h"
#include "tests/support/attend_process.h"
#include "tests/support/temp_dir.h"

namespace attend {
namespace {

using testing::Attend;
using testing::Contains;
using testing::ReadText;
using testing::Result;

// The targets of every record of RUN/frames.jsonl.
std::vector<nlohmann::json> Targets(const testing::TempDir& dir, const std::string& run) {
  std::vector<nlohmann::json> targets;
  std::istringstream lines(ReadText(dir.File(run + "/frames.jsonl")));
  for (std::string line; std::getline(lines, line);) {
    const nlohmann::json record = nlohmann::json::parse(line);
    for (const nlohmann::json& t : record["targets"]) targets.push_back(t);
  }
  return targets;
}

TEST(DepthCli, AStereoRunRecordsEachTargetsDisparityAndEvalScoresIt) {
  testing::TempDir dir;
  Result r = Attend(dir, {"synth", testing::ProjectRoot() + "/sequences/lab.yaml", "--out", "seq",
                          "--frames", "30"});
  ASSERT_EQ(r.status, 0) << r.err;
  r = Attend(dir, {"run", "--sequence", "seq", "--out", "run", "--quiet", "--set",
                   "output.dump=[]"});
  ASSERT_EQ(r.status, 0) << r.err;
  int with_disparity = 0;
  // synth writes seq/calib.yaml: every position's depth is f B / d, one constant for all.
  double focal_baseline = -1.0;
  for (const nlohmann::json& t : Targets(dir, "run")) {
    const std::string state = t["state"];
    if (state == "new" || state == "tracked" || state == "resumed") {
      if (t.contains("disparity_px")) {
        ++with_disparity;
        const double d = t["disparity_px"].get<double>();
        EXPECT_GE(d, 0.0) << t.dump();
        EXPECT_GT(t["disparity_sd_px"].get<double>(), 0.0) << t.dump();
        if (d <= 0.5) continue;
        ASSERT_TRUE(t.contains("position_m")) << t.dump();
        const double fb = t["position_m"][2].get<double>() * d;
        if (focal_baseline < 0) focal_baseline = fb;
        EXPECT_NEAR(fb, focal_baseline, 0.01 * focal_baseline + 1e-3 * d) << t.dump();
        EXPECT_GT(t["position_sd_m"][2].get<double>(), 0.0) << t.dump();
      }
    } else {
      EXPECT_FALSE(t.contains("disparity_px")) << t.dump();
    }
  }
  EXPECT_GT(with_disparity, 30);
  r = Attend(dir, {"eval", "run"});
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json depth = nlohmann::json::parse(r.out)["target_depth"];
  ASSERT_TRUE(depth.is_object()) << r.out;
  EXPECT_GT(depth["matches"].get<int>(), 30) << depth.dump();
  // The bar (docs/STEREO3D.md): median error within 0.25 px, depth within 2 %.
  EXPECT_LT(depth["median_abs_error_px"].get<double>(), 0.25) << depth.dump();
  EXPECT_LT(depth["median_depth_error"].get<double>(), 0.02) << depth.dump();

  // The same frames as a monocular source: no disparity, and no target_depth in eval.
  r = Attend(dir, {"run", "--images", "seq/left", "--out", "mono", "--quiet", "--set",
                   "output.dump=[]"});
  ASSERT_EQ(r.status, 0) << r.err;
  for (const nlohmann::json& t : Targets(dir, "mono")) {
    EXPECT_FALSE(t.contains("disparity_px")) << t.dump();
    EXPECT_FALSE(t.contains("position_m")) << t.dump();
  }

  // With depth off, a stereo run records none either.
  r = Attend(dir, {"run", "--sequence", "seq", "--out", "off", "--quiet", "--frames", "0:5",
                   "--set", "output.dump=[]", "--set", "depth.method=off"});
  ASSERT_EQ(r.status, 0) << r.err;
  for (const nlohmann::json& t : Targets(dir, "off")) EXPECT_FALSE(t.contains("disparity_px"));
}

TEST(DepthCli, RegionsNeedGroundTruthAndAShare) {
  testing::TempDir dir;
  Result r = Attend(dir, {"disparity", "l.png", "r.png", "--out", "d.pfm", "--regions", "0.01"});
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_TRUE(Contains(r.err, "--gt")) << r.err;
  r = Attend(dir, {"disparity", "l.png", "r.png", "--out", "d.pfm", "--gt", "g.pfm", "--regions",
                   "2"});
  EXPECT_EQ(r.status, 2) << r.err;
}

}  // namespace
}  // namespace attend
