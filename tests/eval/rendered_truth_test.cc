// The scene truth read from a rendered street scene (eval/rendered_truth.h): a tiny scene
// rendered here, whose depths, classes and horizon follow from the camera by construction.
#include "eval/rendered_truth.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "synth/render_sequence.h"
#include "synth/scene.h"
#include "tests/support/temp_dir.h"
#include "util/error.h"

namespace attend {
namespace {

namespace fs = std::filesystem;

// f = 60, B = 0.5, h = 1.5, no pitch: the horizon is row 23.5 and a ground pixel of row v is
// at depth f h / (v - 23.5) = 90 / (v - 23.5). A car 10 m ahead covers rows 24..32.
const char* const kScene = R"(name: tiny
width: 64
height: 48
frames: 3
fps: 25
seed: 4
camera: {focal_px: 60, baseline_m: 0.5, height_m: 1.5}
noise: {left: 0, right: 0}
street: {}
objects:
  - {id: 3, kind: car, size: [2, 1.5], ground_path: [{frame: 0, lateral: 0, distance: 10}]}
)";

std::string RenderTiny(const testing::TempDir& dir) {
  const std::string out = (fs::path(dir.path()) / "seq").string();
  RenderSequence(ParseScene(kScene, "tiny.yaml"), out, SynthOptions());
  return out;
}

TEST(RenderedTruth, PointsObjectsAndHorizonOfATinyStreet) {
  const testing::TempDir dir;
  const std::string seq = RenderTiny(dir);
  EXPECT_TRUE(HasRenderedTruth(seq + "/gt"));
  const SceneTruth truth = ReadRenderedTruth(seq);
  ASSERT_EQ(truth.size(), 3u);
  const FrameTruth& frame = truth.at(1);
  EXPECT_EQ(frame.image_size, cv::Size(64, 48));
  ASSERT_TRUE(frame.horizon.valid());
  EXPECT_DOUBLE_EQ(frame.horizon.HorizonV(10), 23.5);
  ASSERT_EQ(frame.objects.size(), 1u);
  EXPECT_EQ(frame.objects[0].id, 3);
  EXPECT_EQ(frame.objects[0].box, cv::Rect2d(26, 24, 12, 9));
  EXPECT_NEAR(frame.objects[0].depth_m, 10.0, 1e-9);
  int ground = 0, object = 0;
  for (const TruthPoint& p : frame.points) {
    // On the step-2 grid, never on the sky rows above the horizon.
    EXPECT_EQ(static_cast<int>(p.u) % kRenderedPointStep, 0);
    EXPECT_GT(p.v, 23.5f);
    if (p.ground) {
      ++ground;
      EXPECT_NEAR(p.depth_m, 90.0 / (p.v - 23.5), 1e-4 * p.depth_m);
    } else {
      ++object;
      EXPECT_NEAR(p.depth_m, 10.0, 1e-4);
    }
  }
  // Rows 24..46 even: 12 rows of 32 grid columns; the car covers rows 24..32 even (5) and
  // columns 26..36 even (6).
  EXPECT_EQ(object, 30);
  EXPECT_EQ(ground, 12 * 32 - 30);
}

TEST(RenderedTruth, BadFilesAreInputErrorsNamingThem) {
  const testing::TempDir dir;
  const std::string seq = RenderTiny(dir);
  {
    std::ofstream(seq + "/gt/horizon.txt") << "# a b c\n0 0 -3\n";
    try {
      ReadRenderedTruth(seq);
      FAIL() << "a horizon with b = 0 was read";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("horizon.txt:2"), std::string::npos) << e.what();
    }
  }
  std::ofstream(seq + "/gt/horizon.txt") << "0 1 -23.5\n";
  fs::remove(seq + "/gt/disparity/000002.pfm");
  try {
    ReadRenderedTruth(seq);
    FAIL() << "a missing disparity map was not noticed";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("000002.pfm"), std::string::npos) << e.what();
  }
  fs::remove_all(seq + "/gt/classes");
  EXPECT_FALSE(HasRenderedTruth(seq + "/gt"));
  EXPECT_THROW(ReadRenderedTruth(seq), InputError);
}

}  // namespace
}  // namespace attend
