// The description of a synthetic stereo scene (docs/SYNTH.md): a textured background plane,
// fronto-parallel objects that move along keyframed paths, a stereo camera, global brightness
// keyframes and sensor noise. A scene with a `street` block is a street scene instead: a
// ground plane to the horizon, a sky, a row of facades and objects standing on the ground,
// seen by a camera that drives forward (issue 55). Scenes are read from YAML through ParamBlock
// only.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "util/option_fields.h"

namespace attend {

// An RGB colour, each channel in [0, 255].
using Rgb = std::array<double, 3>;

enum class SynthShape { kRectangle, kEllipse, kTriangle, kBlob };

// "rectangle", "ellipse", "triangle", "blob".
const char* SynthShapeName(SynthShape shape);

// Where an object's centre is at one frame: left-image pixels and depth in metres.
struct PathKeyframe {
  int frame = 0;
  double x = 0.0;
  double y = 0.0;
  double depth = 1.0;
  // The keys of a `path` element (frame, x, y, depth): each required.
  static const OptionFields<PathKeyframe>& Fields();
};

// The global gain that multiplies every surface colour at one frame.
struct GainKeyframe {
  int frame = 0;
  double gain = 1.0;
  // The keys of a `brightness` element (frame, gain): each required.
  static const OptionFields<GainKeyframe>& Fields();
};

// A sinusoidal offset added to the path (a waving hand): amplitude * sin(2 pi (t / period +
// phase)).
struct Oscillation {
  double amplitude_x = 0.0;  // pixels
  double amplitude_y = 0.0;  // pixels
  double period = 0.0;       // frames; 0 means no oscillation
  double phase = 0.0;        // fraction of a period, [0, 1)
  // The keys of an object's `oscillation` (amplitude [x, y], period, phase).
  static const OptionFields<Oscillation>& Fields();
};

// The deformation of a blob: its radius at angle theta and frame t is the base ellipse's times
// 1 + amplitude * g(theta, t), with g a sum of two travelling waves of `lobes` and `lobes + 1`
// lobes, |g| <= 1.
struct BlobDeformation {
  int lobes = 5;            // [2, 16]
  double amplitude = 0.25;  // [0, 0.6]
  double period = 40.0;     // frames for one cycle of the first wave, > 0
  // The keys of an object's `blob`.
  static const OptionFields<BlobDeformation>& Fields();
};

// Where an object standing on the ground of a street scene is at one frame: its centre's
// lateral position and its distance along the road, both in the world (the camera starts at
// lateral 0, distance 0 and drives along +distance), metres.
struct GroundKeyframe {
  int frame = 0;
  double lateral = 0.0;   // metres, positive to the right
  double distance = 10.0;  // metres, along the road from the camera's position at frame 0
  // The keys of a `ground_path` element (frame, lateral, distance): each required.
  static const OptionFields<GroundKeyframe>& Fields();
};

struct SceneObject {
  int id = 1;                   // >= 1, unique; 0 is the background in id maps
  std::string name = "object";  // for people reading the scene
  // The ground-truth kind: "object", "skin", or a street kind "car", "person", "cyclist".
  std::string kind = "object";
  SynthShape shape = SynthShape::kRectangle;
  double width_m = 0.2;   // physical width, metres, > 0
  double height_m = 0.2;  // physical height, metres, > 0
  Rgb colour = {128, 128, 128};
  double texture = 0.0;            // texture amplitude, grey levels, [0, 255]
  double texture_cell_m = 0.02;    // texture lattice spacing on the surface, metres, > 0
  std::vector<PathKeyframe> path;  // at least one, frames strictly increasing (not in streets)
  // Street scenes only, instead of `path`: at least one, frames strictly increasing. The
  // object stands on the ground, its base on the ground plane.
  std::vector<GroundKeyframe> ground_path;
  Oscillation oscillation;
  BlobDeformation blob;  // used only when shape is kBlob
  int entry = 0;         // first frame present
  int exit = -1;         // last frame present (inclusive); -1: to the end
  // The keys of an `objects` element, but for its nested path, oscillation and blob.
  static const OptionFields<SceneObject>& Fields();
};

struct SceneBackground {
  double depth_m = 8.0;  // > 0, behind every object
  Rgb colour = {128, 128, 128};
  double texture = 12.0;        // grey levels, [0, 255]
  double texture_cell_m = 0.1;  // metres, > 0
  // The keys of `background`.
  static const OptionFields<SceneBackground>& Fields();
};

// The road surface of a street scene, the ground plane Y = 0 (docs/SYNTH.md, "Street scenes").
struct StreetGround {
  Rgb colour = {92, 92, 96};  // asphalt
  double texture = 18.0;      // grey levels, [0, 255]
  double texture_cell_m = 0.3;
  double road_width_m = 9.0;  // the road, centred on the camera's start; beyond it the verge
  Rgb verge_colour = {140, 136, 126};
  double lane_width_m = 3.5;  // dashed markings between lanes; 0: none
  double marking_width_m = 0.15;
  double dash_m = 3.0;  // length of a dash along the road
  double gap_m = 6.0;   // between dashes
  Rgb marking_colour = {225, 225, 215};
  static const OptionFields<StreetGround>& Fields();
};

// The sky: a vertical gradient by elevation, with little texture and no disparity.
struct StreetSky {
  Rgb horizon_colour = {205, 218, 232};
  Rgb zenith_colour = {120, 165, 220};
  double gradient_deg = 25.0;  // elevation at which the zenith colour is reached, (0, 90]
  double texture = 3.0;        // grey levels, [0, 255]
  static const OptionFields<StreetSky>& Fields();
};

// A row of facades standing on the ground across the road's end, at a fixed distance in the
// world; each facade's height and colour are drawn from the seed. Distance 0: no backdrop.
struct StreetBackdrop {
  double distance_m = 0.0;  // along the road from the camera's start; 0: none
  double min_height_m = 6.0;
  double max_height_m = 18.0;
  double facade_width_m = 12.0;
  Rgb colour = {150, 132, 118};
  double colour_spread = 30.0;    // each facade's channels vary by up to this, grey levels
  double texture = 12.0;          // grey levels
  double texture_cell_m = 0.5;
  double window_contrast = 45.0;  // how much darker the windows are; 0: no windows
  static const OptionFields<StreetBackdrop>& Fields();
};

struct StreetSetting {
  StreetGround ground;
  StreetSky sky;
  StreetBackdrop backdrop;
};

struct Scene {
  std::string name = "synthetic";
  std::string source;        // the file it was read from ("" when built in code)
  int width = 320;           // pixels, [16, 8192]
  int height = 240;          // pixels, [16, 8192]
  int frames = 120;          // >= 1
  double fps = 25.0;         // > 0
  std::uint64_t seed = 1;    // textures, blob phases and noise derive from it
  double focal_px = 300.0;   // > 0
  double baseline_m = 0.12;  // > 0
  // Street scenes only (camera block): the left camera's height above the ground, its pitch
  // (positive looks down) and its forward speed.
  double camera_height_m = 1.5;  // > 0
  double pitch_deg = 0.0;        // [-30, 30]
  double speed_mps = 0.0;        // [0, 100]
  double noise_left = 1.0;   // Gaussian noise sigma of the left view, grey levels, [0, 100]
  double noise_right = 1.0;  // same for the right view
  SceneBackground background;
  std::vector<GainKeyframe> brightness;  // empty: gain 1; frames strictly increasing
  std::vector<SceneObject> objects;
  // Set by a `street` block: a street scene; `background` is then not used.
  std::optional<StreetSetting> street;

  // "" when valid; otherwise names the field and the broken constraint.
  std::string Check() const;
  // The top-level keys of a scene file (name, width, height, frames, fps, seed), and those of
  // its `camera` and `noise` blocks, which set fields of the scene too.
  static const OptionFields<Scene>& Fields();
  static const OptionFields<Scene>& CameraFields();
  static const OptionFields<Scene>& NoiseFields();
};

// Reads a scene file. Missing file, YAML errors, unknown keys (with the closest valid key),
// wrong types, values out of range and inconsistent values: ConfigError naming file and line.
Scene LoadScene(const std::string& path);
// The same for text in memory; `source` names it in messages.
Scene ParseScene(const std::string& text, const std::string& source);

// Linear interpolation between keyframes, held constant before the first and after the last.
// The returned keyframe's `frame` is `frame`.
PathKeyframe InterpolatePath(const std::vector<PathKeyframe>& path, int frame);
GroundKeyframe InterpolateGroundPath(const std::vector<GroundKeyframe>& path, int frame);
double InterpolateGain(const std::vector<GainKeyframe>& brightness, int frame);

}  // namespace attend
