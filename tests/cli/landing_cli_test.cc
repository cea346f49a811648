// attend eval on a rendered street scene (issue 55): attend synth renders a small street,
// attend run attends to it with the default configuration, and attend eval adds the "landing"
// block after its usual keys, with counts and shares that agree with each other.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tests/cli/attend_cli.h"
#include "tests/support/attend_process.h"
#include "tests/support/temp_dir.h"

namespace attend {
namespace {

using testing::Attend;
using testing::Result;

// Small and short so that the three commands take seconds: a car ahead, a person at the
// roadside and facades under a sky, the camera driving at 5 m/s.
const char* const kStreet = R"(name: small_street
width: 160
height: 96
frames: 12
fps: 25
seed: 3
camera: {focal_px: 120, baseline_m: 0.5, height_m: 1.5, speed_mps: 5}
street:
  backdrop: {distance: 60}
objects:
  - {id: 1, kind: car, size: [1.8, 1.5], colour: [200, 30, 30], texture: 10,
     ground_path: [{frame: 0, lateral: 0, distance: 9}]}
  - {id: 2, kind: person, shape: ellipse, size: [0.6, 1.75], colour: [40, 160, 60],
     texture: 12, ground_path: [{frame: 0, lateral: 3, distance: 14}]}
)";

TEST(LandingCli, EvalOfARenderedStreetHasALandingBlock) {
  testing::TempDir dir;
  dir.Write("street.yaml", kStreet);
  Result r = Attend(dir, {"synth", "street.yaml", "--out", "seq"});
  ASSERT_EQ(r.status, 0) << r.err;
  r = Attend(dir, {"run", "--sequence", "seq", "--out", "run", "--quiet"});
  ASSERT_EQ(r.status, 0) << r.err;
  r = Attend(dir, {"eval", "run"});
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::ordered_json report = nlohmann::ordered_json::parse(r.out);
  std::vector<std::string> keys;
  for (const auto& [key, value] : report.items()) keys.push_back(key);
  ASSERT_FALSE(keys.empty());
  EXPECT_EQ(keys.back(), "landing");
  EXPECT_EQ(keys[0], "run");
  EXPECT_TRUE(report.contains("per_object"));

  const nlohmann::ordered_json& landing = report["landing"];
  EXPECT_EQ(landing["frames"], 12);
  EXPECT_EQ(landing["frames_without_truth"], 0);
  EXPECT_EQ(landing["objects"], 2);
  const int target_frames = landing["target_frames"];
  ASSERT_GT(target_frames, 0) << landing.dump();
  // The categories overlap, but every target-frame is in one of them or elsewhere; elsewhere
  // excludes the other three; the sky is a part of what has no depth.
  const int on_object = landing["on_object"], on_sky = landing["on_sky"];
  const int on_ground = landing["on_ground"], elsewhere = landing["elsewhere"];
  EXPECT_GE(on_object + on_sky + on_ground + elsewhere, target_frames);
  EXPECT_LE(elsewhere, target_frames);
  EXPECT_LE(on_sky, landing["without_depth"].get<int>());
  for (const char* share : {"on_object_share", "on_sky_share", "on_ground_share",
                            "without_depth_share", "elsewhere_share", "object_share_in_view"}) {
    const double value = landing[share];
    EXPECT_GE(value, 0.0) << share;
    EXPECT_LE(value, 1.0) << share;
  }
  EXPECT_DOUBLE_EQ(landing["on_object_share"].get<double>(),
                   static_cast<double>(on_object) / target_frames);
  EXPECT_EQ(landing["per_object"].size(), 2u);
}

}  // namespace
}  // namespace attend
