#include "synth/scene.h"

#include <gtest/gtest.h>

#include "tests/support/error_message.h"
#include "tests/support/temp_dir.h"
#include "util/error.h"

namespace attend {
namespace {

using testing::ConfigErrorOf;
using testing::ErrorOf;
using testing::InputErrorOf;

// A valid scene with one object; `object_extra` is appended to the object's keys.
std::string SceneText(const std::string& object_extra = "") {
  return "name: test\n"                                       // 1
         "width: 64\n"                                        // 2
         "height: 48\n"                                       // 3
         "frames: 10\n"                                       // 4
         "background: {depth: 5, colour: [120, 120, 120]}\n"  // 5
         "objects:\n"                                         // 6
         "  - id: 1\n"                                        // 7
         "    size: [0.2, 0.1]\n"                             // 8
         "    path:\n"                                        // 9
         "      - {frame: 0, x: 10, y: 20, depth: 2}\n"       // 10
         "      - {frame: 8, x: 50, y: 20, depth: 1}\n" +     // 11
         object_extra;                                        // 12...
}

TEST(Scene, DefaultsAreValid) {
  EXPECT_EQ(Scene().Check(), "");
  Scene scene;
  scene.objects.push_back(SceneObject());
  EXPECT_NE(scene.Check().find("path needs at least one keyframe"), std::string::npos);
  scene.objects[0].path.push_back(PathKeyframe());
  EXPECT_EQ(scene.Check(), "");
}

TEST(Scene, ReadsEveryKey) {
  const Scene scene = ParseScene(
      "name: full\nwidth: 100\nheight: 80\nframes: 30\nfps: 12.5\nseed: 42\n"
      "camera: {focal_px: 150, baseline_m: 0.2}\n"
      "noise: {left: 2, right: 3}\n"
      "background: {depth: 7, colour: [10, 20, 30], texture: 5, texture_cell: 0.3}\n"
      "brightness:\n  - {frame: 0, gain: 1}\n  - {frame: 10, gain: 0.5}\n"
      "objects:\n"
      "  - id: 4\n    name: hand\n    kind: skin\n    shape: blob\n    size: [0.1, 0.2]\n"
      "    colour: [220, 170, 140]\n    texture: 6\n    texture_cell: 0.01\n"
      "    path: [{frame: 2, x: 5, y: 6, depth: 1.5}]\n"
      "    oscillation: {amplitude: [12, -3], period: 16, phase: 0.25}\n"
      "    blob: {lobes: 7, amplitude: 0.3, period: 20}\n"
      "    entry: 3\n    exit: 20\n",
      "full.yaml");
  EXPECT_EQ(scene.name, "full");
  EXPECT_EQ(scene.source, "full.yaml");
  EXPECT_EQ(scene.width, 100);
  EXPECT_EQ(scene.height, 80);
  EXPECT_EQ(scene.frames, 30);
  EXPECT_DOUBLE_EQ(scene.fps, 12.5);
  EXPECT_EQ(scene.seed, 42u);
  EXPECT_DOUBLE_EQ(scene.focal_px, 150);
  EXPECT_DOUBLE_EQ(scene.baseline_m, 0.2);
  EXPECT_DOUBLE_EQ(scene.noise_left, 2);
  EXPECT_DOUBLE_EQ(scene.noise_right, 3);
  EXPECT_DOUBLE_EQ(scene.background.depth_m, 7);
  EXPECT_EQ(scene.background.colour, (Rgb{10, 20, 30}));
  EXPECT_DOUBLE_EQ(scene.background.texture, 5);
  EXPECT_DOUBLE_EQ(scene.background.texture_cell_m, 0.3);
  ASSERT_EQ(scene.brightness.size(), 2u);
  EXPECT_DOUBLE_EQ(scene.brightness[1].gain, 0.5);
  ASSERT_EQ(scene.objects.size(), 1u);
  const SceneObject& o = scene.objects[0];
  EXPECT_EQ(o.id, 4);
  EXPECT_EQ(o.name, "hand");
  EXPECT_EQ(o.kind, "skin");
  EXPECT_EQ(o.shape, SynthShape::kBlob);
  EXPECT_DOUBLE_EQ(o.width_m, 0.1);
  EXPECT_DOUBLE_EQ(o.height_m, 0.2);
  EXPECT_EQ(o.colour, (Rgb{220, 170, 140}));
  EXPECT_DOUBLE_EQ(o.texture, 6);
  EXPECT_DOUBLE_EQ(o.texture_cell_m, 0.01);
  ASSERT_EQ(o.path.size(), 1u);
  EXPECT_EQ(o.path[0].frame, 2);
  EXPECT_DOUBLE_EQ(o.path[0].depth, 1.5);
  EXPECT_DOUBLE_EQ(o.oscillation.amplitude_x, 12);
  EXPECT_DOUBLE_EQ(o.oscillation.amplitude_y, -3);
  EXPECT_DOUBLE_EQ(o.oscillation.period, 16);
  EXPECT_DOUBLE_EQ(o.oscillation.phase, 0.25);
  EXPECT_EQ(o.blob.lobes, 7);
  EXPECT_DOUBLE_EQ(o.blob.amplitude, 0.3);
  EXPECT_DOUBLE_EQ(o.blob.period, 20);
  EXPECT_EQ(o.entry, 3);
  EXPECT_EQ(o.exit, 20);
}

TEST(Scene, OmittedKeysTakeTheirDefaults) {
  const Scene scene = ParseScene(SceneText(), "d.yaml");
  const Scene defaults;
  EXPECT_EQ(scene.seed, defaults.seed);
  EXPECT_DOUBLE_EQ(scene.focal_px, defaults.focal_px);
  EXPECT_DOUBLE_EQ(scene.noise_left, defaults.noise_left);
  const SceneObject& o = scene.objects.at(0);
  EXPECT_EQ(o.name, "object1");
  EXPECT_EQ(o.kind, "object");
  EXPECT_EQ(o.shape, SynthShape::kRectangle);
  EXPECT_EQ(o.entry, 0);
  EXPECT_EQ(o.exit, -1);
  EXPECT_DOUBLE_EQ(o.oscillation.period, 0);
}

TEST(Scene, UnknownKeyNamesLineAndClosestKey) {
  std::string message =
      ConfigErrorOf([] { ParseScene(SceneText("    colr: [1, 2, 3]\n"), "s.yaml"); });
  EXPECT_NE(message.find("s.yaml:12: unknown key 'colr' in objects.0"), std::string::npos)
      << message;
  EXPECT_NE(message.find("did you mean 'colour'"), std::string::npos) << message;
  // A misspelt required key is reported as the typo, not as a missing key.
  message = ConfigErrorOf([] {
    ParseScene(
        "background: {depth: 5}\nobjects:\n  - id: 1\n    size: [1, 1]\n"
        "    path: [{frame: 0, x: 1, y: 2, dpth: 3}]\n",
        "k.yaml");
  });
  EXPECT_NE(message.find("k.yaml:5: unknown key 'dpth'"), std::string::npos) << message;
  EXPECT_NE(message.find("did you mean 'depth'"), std::string::npos) << message;
  message = ConfigErrorOf([] { ParseScene("camera: {focal: 300}\n", "c.yaml"); });
  EXPECT_NE(message.find("c.yaml:1: unknown key 'focal' in camera"), std::string::npos) << message;
  message = ConfigErrorOf([] { ParseScene("widht: 30\n", "w.yaml"); });
  EXPECT_NE(message.find("did you mean 'width'"), std::string::npos) << message;
}

TEST(Scene, BadValuesNameKeyAndLine) {
  struct Case {
    std::string extra;
    std::string expected;
  };
  const std::vector<Case> cases = {
      {"    colour: [300, 0, 0]\n", "s.yaml:12: objects.0.colour: element 0 = 300 out of range"},
      {"    entry: 5\n    exit: 2\n", "s.yaml:13: objects.0.exit: exit 2 is before entry 5"},
      {"    entry: 10\n", "s.yaml:12: objects.0.entry: frame 10 is after the last frame"},
      {"    shape: star\n", "s.yaml:12: objects.0.shape: 'star' is not one of"},
      {"    kind: face\n", "s.yaml:12: objects.0.kind: 'face' is not one of object, skin"},
      {"    blob: {lobes: 3}\n", "s.yaml:12: objects.0.blob: only valid with shape: blob"},
      {"    texture: -1\n", "s.yaml:12: objects.0.texture: value -1 out of range"},
      {"    texture_cell: .inf\n",
       "s.yaml:12: objects.0.texture_cell: value .inf is not a finite number"},
      {"    oscillation: {amplitude: [.nan, 0], period: 4}\n",
       "s.yaml:12: objects.0.oscillation.amplitude: element 0 = .nan is not a finite number"},
      {"    oscillation: {amplitude: [3, 0]}\n",
       "s.yaml:12: objects.0.oscillation.period: required key is missing"},
      {"  - id: 1\n    size: [1, 1]\n    path: [{frame: 0, x: 0, y: 0, depth: 1}]\n",
       "s.yaml:12: objects.1.id: id 1 is already used at line 7"},
  };
  for (const Case& c : cases) {
    const std::string message = ConfigErrorOf([&] { ParseScene(SceneText(c.extra), "s.yaml"); });
    EXPECT_NE(message.find(c.expected), std::string::npos) << c.extra << " -> " << message;
  }
  std::string message = ConfigErrorOf([] {
    ParseScene(
        "objects:\n  - id: 1\n    size: [1, 1]\n"
        "    path: [{frame: 0, x: 0, y: 0, depth: -1}]\n",
        "n.yaml");
  });
  EXPECT_NE(message.find(
                "n.yaml:4: objects.0.path.0.depth: value -1 out of range: must be in (0, 1000000]"),
            std::string::npos)
      << message;
  message = ConfigErrorOf([] {
    ParseScene(
        "background: {depth: 3}\nobjects:\n  - id: 1\n    size: [1, 1]\n"
        "    path: [{frame: 0, x: 0, y: 0, depth: 4}]\n",
        "b.yaml");
  });
  EXPECT_NE(message.find("b.yaml:5: objects.0.path.0.depth: depth 4 m is not in front of the "
                         "background"),
            std::string::npos)
      << message;
  message = ConfigErrorOf([] {
    ParseScene(
        "objects:\n  - id: 1\n    size: [1, 1]\n    path:\n"
        "      - {frame: 5, x: 0, y: 0, depth: 1}\n      - {frame: 5, x: 1, y: 0, depth: 1}\n",
        "f.yaml");
  });
  EXPECT_NE(message.find("f.yaml:6: objects.0.path.1.frame: keyframe frames must increase"),
            std::string::npos)
      << message;
  message = ConfigErrorOf([] { ParseScene("objects:\n  - id: 1\n    size: [1, 1]\n", "p.yaml"); });
  EXPECT_NE(message.find("objects.0.path: required key is missing"), std::string::npos) << message;
  message = ConfigErrorOf([] { ParseScene("objects:\n  - id: 1\n    path: []\n", "e.yaml"); });
  EXPECT_NE(message.find("objects.0.size: required key is missing"), std::string::npos) << message;
  message = ConfigErrorOf([] { ParseScene("name: ''\n", "m.yaml"); });
  EXPECT_NE(message.find("m.yaml:1: name: must not be empty"), std::string::npos) << message;
  message = ConfigErrorOf([] { ParseScene("width: 8\n", "w.yaml"); });
  EXPECT_NE(message.find("w.yaml:1: width: value 8 out of range: must be in [16, 8192]"),
            std::string::npos)
      << message;
  message = ConfigErrorOf([] {
    ParseScene("brightness:\n  - {frame: 4, gain: 1}\n  - {frame: 2, gain: 0.5}\n", "g.yaml");
  });
  EXPECT_NE(message.find("g.yaml:3: brightness.1.frame: keyframe frames must increase"),
            std::string::npos)
      << message;
}

TEST(Scene, LoadSceneReportsTheFile) {
  testing::TempDir dir;
  const std::string path = dir.Write("scene.yaml", SceneText("    colour: [1, 2]\n"));
  const std::string message = ConfigErrorOf([&] { LoadScene(path); });
  EXPECT_NE(message.find(path + ":12: objects.0.colour: expected 3 elements, got 2"),
            std::string::npos)
      << message;
  EXPECT_NE(ConfigErrorOf([] { LoadScene("/nonexistent/scene.yaml"); }).find("/nonexistent/scene.yaml: the YAML file does not exist"),
            std::string::npos);
  const Scene scene = LoadScene(dir.Write("ok.yaml", SceneText()));
  EXPECT_EQ(scene.source, dir.File("ok.yaml"));
}

TEST(Scene, InterpolatesLinearlyAndHoldsOutsideTheKeyframes) {
  const std::vector<PathKeyframe> path = {{10, 0, 100, 4}, {20, 50, 100, 2}, {30, 50, 0, 2}};
  EXPECT_DOUBLE_EQ(InterpolatePath(path, 0).x, 0);
  EXPECT_DOUBLE_EQ(InterpolatePath(path, 15).x, 25);
  EXPECT_DOUBLE_EQ(InterpolatePath(path, 15).depth, 3);
  EXPECT_DOUBLE_EQ(InterpolatePath(path, 25).y, 50);
  EXPECT_DOUBLE_EQ(InterpolatePath(path, 99).y, 0);
  EXPECT_EQ(InterpolatePath(path, 99).frame, 99);
  EXPECT_DOUBLE_EQ(InterpolateGain({}, 7), 1.0);
  const std::vector<GainKeyframe> gain = {{4, 1.0}, {8, 0.5}};
  EXPECT_DOUBLE_EQ(InterpolateGain(gain, 0), 1.0);
  EXPECT_DOUBLE_EQ(InterpolateGain(gain, 6), 0.75);
  EXPECT_DOUBLE_EQ(InterpolateGain(gain, 100), 0.5);
}

TEST(Scene, BundledScenesLoad) {
  const std::string root = testing::ProjectRoot() + "/sequences/";
  const Scene lab = LoadScene(root + "lab.yaml");
  EXPECT_EQ(lab.width, 320);
  EXPECT_EQ(lab.height, 240);
  EXPECT_GE(lab.frames, 100);
  bool has_face = false, has_waving_hand = false, has_late_arrival = false;
  for (const SceneObject& o : lab.objects) {
    has_face |= o.kind == "skin" && o.shape == SynthShape::kEllipse;
    has_waving_hand |= o.kind == "skin" && o.shape == SynthShape::kBlob && o.oscillation.period > 0;
    has_late_arrival |= o.entry >= 20;
  }
  EXPECT_TRUE(has_face);
  EXPECT_TRUE(has_waving_hand);
  EXPECT_TRUE(has_late_arrival);
  EXPECT_GE(lab.brightness.size(), 3u);

  const Scene occlusions = LoadScene(root + "occlusions.yaml");
  EXPECT_GE(occlusions.objects.size(), 4u);
  const Scene crowd = LoadScene(root + "crowd.yaml");
  EXPECT_GE(crowd.objects.size(), 10u);
  for (const Scene* scene : {&lab, &occlusions, &crowd}) EXPECT_EQ(scene->Check(), "");
}

}  // namespace
}  // namespace attend
