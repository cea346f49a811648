// The description of a synthetic stereo scene (docs/SYNTH.md): a textured background plane,
// fronto-parallel objects that move along keyframed paths, a stereo camera, global brightness
// keyframes and sensor noise. Scenes are read from YAML through ParamBlock only.
#pragma once

#include <array>
#include <cstdint>
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

struct SceneObject {
  int id = 1;                   // >= 1, unique; 0 is the background in id maps
  std::string name = "object";  // for people reading the scene
  std::string kind = "object";  // "object" or "skin": the ground-truth kind
  SynthShape shape = SynthShape::kRectangle;
  double width_m = 0.2;   // physical width, metres, > 0
  double height_m = 0.2;  // physical height, metres, > 0
  Rgb colour = {128, 128, 128};
  double texture = 0.0;            // texture amplitude, grey levels, [0, 255]
  double texture_cell_m = 0.02;    // texture lattice spacing on the surface, metres, > 0
  std::vector<PathKeyframe> path;  // at least one, frames strictly increasing
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
  double noise_left = 1.0;   // Gaussian noise sigma of the left view, grey levels, [0, 100]
  double noise_right = 1.0;  // same for the right view
  SceneBackground background;
  std::vector<GainKeyframe> brightness;  // empty: gain 1; frames strictly increasing
  std::vector<SceneObject> objects;

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
double InterpolateGain(const std::vector<GainKeyframe>& brightness, int frame);

}  // namespace attend
