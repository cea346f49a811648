// Street scenes (docs/SYNTH.md, "Street scenes"): answers known by construction from the
// camera's height, pitch, speed and the pinhole projection.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>

#include "io/ground_truth.h"
#include "io/pfm.h"
#include "synth/render_sequence.h"
#include "synth/renderer.h"
#include "synth/street_renderer.h"
#include "tests/support/temp_dir.h"
#include "util/error.h"

namespace attend {
namespace {

namespace fs = std::filesystem;

// f = 60 px, B = 0.5 m, camera 1.5 m high, 5 m/s at 25 fps (0.2 m a frame), no pitch: the
// principal point's row is (48 - 1) / 2 = 23.5 and a ground row v has disparity
// B (v - 23.5) / 1.5. A car 2 m wide and 1.5 m high stands 10 m ahead on the camera's axis.
const char* const kStreetText = R"(name: tiny_street
width: 64
height: 48
frames: 30
fps: 25
seed: 9
camera: {focal_px: 60, baseline_m: 0.5, height_m: 1.5, speed_mps: 5}
noise: {left: 0, right: 0}
street:
  ground: {lane_width: 0}
objects:
  - {id: 1, kind: car, size: [2, 1.5], colour: [200, 30, 30], texture: 10,
     ground_path: [{frame: 0, lateral: 0, distance: 10}]}
)";

constexpr double kStreetFocal = 60.0;
constexpr double kStreetBaseline = 0.5;
constexpr double kHeight = 1.5;
constexpr double kRowOfHorizon = 23.5;

Scene StreetScene() { return ParseScene(kStreetText, "tiny_street.yaml"); }

TEST(StreetScene, DefaultsAreValid) {
  Scene scene;
  scene.street = StreetSetting();
  EXPECT_EQ(scene.Check(), "");
  scene.street->backdrop.max_height_m = 1.0;  // below min_height
  EXPECT_NE(scene.Check().find("max_height"), std::string::npos);
  scene.street->backdrop = StreetBackdrop();
  scene.pitch_deg = 31.0;
  EXPECT_NE(scene.Check().find("camera.pitch_deg"), std::string::npos);
}

TEST(StreetScene, HorizonAtThePrincipalPointsRowWithoutPitch) {
  const Scene scene = StreetScene();
  const std::array<double, 3> line = StreetHorizon(scene);
  EXPECT_DOUBLE_EQ(-line[2] / line[1], kRowOfHorizon);
  EXPECT_DOUBLE_EQ(line[0], 0.0);
  // Looking down 5 degrees lifts it by f tan(5 deg).
  Scene pitched = scene;
  pitched.pitch_deg = 5.0;
  const std::array<double, 3> lifted = StreetHorizon(pitched);
  EXPECT_NEAR(-lifted[2] / lifted[1], kRowOfHorizon - kStreetFocal * std::tan(5.0 * M_PI / 180.0),
              1e-12);
}

TEST(StreetScene, GroundDisparityIsLinearInTheRowBelowTheHorizon) {
  const RenderedFrame frame = SceneRenderer(StreetScene()).Render(0);
  // Column 2 is left of the car at every row; rows 24..47 see the ground.
  for (int v = 24; v < 48; ++v) {
    const double expected = kStreetBaseline * (v - kRowOfHorizon) / kHeight;  // f B / (f h / (v - vh))
    EXPECT_NEAR(frame.disparity.at<float>(v, 2), expected, 1e-5 * expected) << "row " << v;
    EXPECT_EQ(frame.classes.at<std::uint8_t>(v, 2), 2) << "row " << v;
  }
}

TEST(StreetScene, SkyHasNoDisparityAndClassThree) {
  const RenderedFrame frame = SceneRenderer(StreetScene()).Render(0);
  for (int v = 0; v < 24; ++v) {
    for (int u = 0; u < 64; ++u) {
      ASSERT_EQ(frame.disparity.at<float>(v, u), 0.f) << u << ", " << v;
      ASSERT_EQ(frame.classes.at<std::uint8_t>(v, u), 3) << u << ", " << v;
    }
  }
}

TEST(StreetScene, ObjectBaseRowFollowsFromItsDepth) {
  const RenderedFrame frame = SceneRenderer(StreetScene()).Render(0);
  // The base at Z = 10 m projects to row 23.5 + f h / Z = 32.5; pixel centres strictly above
  // it are covered, so row 32 is the car's lowest and row 33 ground. Its top, 1.5 m up, is row
  // 23.5 exactly: rows 24..32, 9 rows. Its width f 2 / 10 = 12 px about column 31.5.
  ASSERT_EQ(frame.objects.size(), 1u);
  const GtObject& car = frame.objects[0];
  EXPECT_EQ(car.box, cv::Rect2d(26, 24, 12, 9));
  EXPECT_EQ(car.kind, "car");
  EXPECT_NEAR(car.visible_fraction, 1.0, 1e-9);
  EXPECT_EQ(frame.left_ids.at<int>(32, 31), 1);
  EXPECT_EQ(frame.left_ids.at<int>(33, 31), 0);
  EXPECT_EQ(frame.classes.at<std::uint8_t>(32, 31), 1);
  EXPECT_EQ(frame.classes.at<std::uint8_t>(33, 31), 2);
  EXPECT_FLOAT_EQ(frame.disparity.at<float>(28, 31), static_cast<float>(kStreetFocal * kStreetBaseline / 10));
}

TEST(StreetScene, StaticObjectApproachesAsTheCameraDrives) {
  const SceneRenderer renderer(StreetScene());
  double previous = 0.0;
  for (const int t : {0, 10, 20, 29}) {
    const RenderedFrame frame = renderer.Render(t);
    const double depth = 10.0 - 5.0 * t / 25.0;
    const double expected = kStreetFocal * kStreetBaseline / depth;
    ASSERT_EQ(frame.objects.size(), 1u);
    EXPECT_NEAR(*frame.objects[0].disparity, expected, 1e-9) << "frame " << t;
    EXPECT_NEAR(frame.disparity.at<float>(26, 31), expected, 1e-5) << "frame " << t;
    EXPECT_GT(expected, previous);
    previous = expected;
  }
}

TEST(StreetScene, RightViewSeesTheObjectShiftedByItsDisparity) {
  const RenderedFrame frame = SceneRenderer(StreetScene()).Render(0);
  // d = f B / Z = 3 px: the car's columns 26..37 in the left view are 23..34 in the right.
  for (int u = 20; u < 40; ++u) {
    EXPECT_EQ(frame.right_ids.at<int>(28, u), u >= 23 && u <= 34 ? 1 : 0) << "column " << u;
  }
}

TEST(StreetScene, ObjectsAreReadOnlyWithAGroundPathInStreets) {
  EXPECT_THROW(ParseScene(R"(street: {}
objects: [{id: 1, size: [1, 1], path: [{frame: 0, x: 1, y: 1, depth: 2}]}]
)", "s.yaml"),
               ConfigError);
  EXPECT_THROW(ParseScene(R"(objects: [{id: 1, size: [1, 1], ground_path: [{frame: 0, lateral: 1,
  distance: 2}]}]
)", "s.yaml"),
               ConfigError);
  EXPECT_THROW(ParseScene("camera: {height_m: 2}\n", "s.yaml"), ConfigError);
  EXPECT_THROW(ParseScene("street: {backdrop: {min_height: 9, max_height: 3}}\n", "s.yaml"),
               ConfigError);
}

TEST(StreetScene, SequenceHoldsClassesAndTheHorizon) {
  const testing::TempDir dir;
  const std::string out = (fs::path(dir.path()) / "seq").string();
  SynthOptions options;
  options.frames = 2;
  RenderSequence(StreetScene(), out, options);
  const cv::Mat classes = cv::imread(out + "/gt/classes/000001.png", cv::IMREAD_UNCHANGED);
  ASSERT_EQ(classes.type(), CV_8UC1);
  EXPECT_EQ(classes.at<std::uint8_t>(0, 0), 3);
  EXPECT_EQ(classes.at<std::uint8_t>(47, 0), 2);
  std::ifstream horizon(out + "/gt/horizon.txt");
  std::string line;
  std::getline(horizon, line);
  while (!line.empty() && line[0] == '#') std::getline(horizon, line);
  EXPECT_EQ(line, "0 1 -23.5");
  const cv::Mat disparity = ReadPfmOneChannel(GtDisparityPath(out, 0), "gt");
  EXPECT_EQ(disparity.at<float>(0, 0), 0.f);
}

TEST(StreetScene, BundledStreetScenesLoad) {
  for (const char* name : {"street_a.yaml", "street_b.yaml"}) {
    const Scene scene = LoadScene(testing::ProjectRoot() + "/sequences/" + name);
    ASSERT_TRUE(scene.street.has_value()) << name;
    EXPECT_EQ(scene.Check(), "") << name;
    EXPECT_GT(scene.speed_mps, 0.0) << name;
    EXPECT_GT(scene.street->backdrop.distance_m, 0.0) << name;
    bool car = false, person = false, cyclist = false, late = false;
    for (const SceneObject& o : scene.objects) {
      car |= o.kind == "car";
      person |= o.kind == "person";
      cyclist |= o.kind == "cyclist";
      late |= o.entry > 0;
    }
    EXPECT_TRUE(car && person && cyclist && late) << name;
  }
}

constexpr std::uint64_t kLabHash = 15638641566511338956ULL;

// FNV-1a over a matrix's bytes.
std::uint64_t Fnv(const cv::Mat& m, std::uint64_t h) {
  for (int y = 0; y < m.rows; ++y) {
    const auto* p = m.ptr<std::uint8_t>(y);
    for (size_t i = 0; i < m.cols * m.elemSize(); ++i) h = (h ^ p[i]) * 0x100000001b3ULL;
  }
  return h;
}

// The lab scene renders to the bytes it rendered before street scenes existed (the hash was
// taken from the renderer of commit b61caea): the street mode leaves old scenes untouched.
TEST(StreetScene, LabSceneUnchanged) {
  const SceneRenderer renderer(LoadScene(testing::ProjectRoot() + "/sequences/lab.yaml"));
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (const int t : {0, 77}) {
    const RenderedFrame frame = renderer.Render(t);
    EXPECT_TRUE(frame.classes.empty());
    h = Fnv(frame.left, Fnv(frame.right, Fnv(frame.disparity, h)));
  }
  EXPECT_EQ(h, kLabHash);
}

}  // namespace
}  // namespace attend
