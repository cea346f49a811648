#include "synth/scene.h"

#include <algorithm>
#include <filesystem>
#include <initializer_list>
#include <map>
#include <sstream>

#include "config/param_block.h"
#include "util/error.h"
#include "util/limits.h"

namespace attend {

const char* SynthShapeName(SynthShape shape) {
  switch (shape) {
    case SynthShape::kRectangle:
      return "rectangle";
    case SynthShape::kEllipse:
      return "ellipse";
    case SynthShape::kTriangle:
      return "triangle";
    case SynthShape::kBlob:
      return "blob";
  }
  return "unknown";
}

namespace {

constexpr int kMinImageSide = 16;
constexpr int kMaxImageSide = 8192;
// The renderer keeps several float planes per object and image: about 50 bytes a pixel at
// 8 objects. 4K UHD (3840 x 2160) is the largest image it renders, in about 0.5 GB.
constexpr long kMaxImagePixels = 3840L * 2160L;
constexpr double kMaxNoiseSigma = 100.0;
constexpr double kMaxGain = 10.0;
constexpr int kMinLobes = 2;
constexpr int kMaxLobes = 16;
constexpr double kMaxBlobAmplitude = 0.6;
// Bounds that keep every number finite (YAML accepts .inf) without limiting real scenes.
constexpr double kLargest = 1e6;

// A length, depth, period or rate: (0, 1e6].
Range Positive() { return Range{0.0, kLargest, true, false}; }
// A position or offset in pixels: [-1e6, 1e6].
Range Coordinate() { return Range::Closed(-kLargest, kLargest); }
bool IsPositive(double value) { return value > 0.0 && value <= kLargest; }
bool IsCoordinate(double value) { return value >= -kLargest && value <= kLargest; }

const std::vector<std::string>& ShapeNames() {
  static const std::vector<std::string> names = {"rectangle", "ellipse", "triangle", "blob"};
  return names;
}

SynthShape ShapeFromName(const std::string& name) {
  if (name == "ellipse") return SynthShape::kEllipse;
  if (name == "triangle") return SynthShape::kTriangle;
  if (name == "blob") return SynthShape::kBlob;
  return SynthShape::kRectangle;
}

std::string Number(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

// Keys whose absence is an error. Called after CheckNoUnknownKeys, so that a misspelt required
// key is reported as the typo it is (with the closest key) rather than as missing.
void RequirePresent(const ParamBlock& block, std::initializer_list<const char*> keys) {
  for (const char* key : keys) {
    if (!block.Has(key)) block.Fail(key, "required key is missing");
  }
}

Rgb ReadColour(const ParamBlock& block, const Rgb& default_value) {
  const std::vector<double> rgb = block.GetDoubles(
      "colour", {default_value[0], default_value[1], default_value[2]}, Range::Closed(0, 255), 3);
  return {rgb[0], rgb[1], rgb[2]};
}

// The line of a block's key, for messages that point at an earlier definition.
std::string LineOf(const ParamBlock& block, const std::string& key) {
  const std::string where = block.Where(key);
  const size_t colon = where.rfind(':');
  return colon == std::string::npos ? where : "line " + where.substr(colon + 1);
}

std::vector<PathKeyframe> ReadPath(const ParamBlock& object, const Scene& scene) {
  std::vector<PathKeyframe> path;
  const std::vector<ParamBlock> keyframes = object.Children("path");
  if (keyframes.empty()) {
    object.Fail("path", "needs at least one keyframe {frame, x, y, depth}");
  }
  for (const ParamBlock& block : keyframes) {
    PathKeyframe key;
    key.frame = block.GetInt("frame", 0, Range::AtLeast(0));
    key.x = block.GetDouble("x", 0.0, Coordinate());
    key.y = block.GetDouble("y", 0.0, Coordinate());
    key.depth = block.GetDouble("depth", 1.0, Positive());
    block.CheckNoUnknownKeys();
    RequirePresent(block, {"frame", "x", "y", "depth"});
    if (key.depth >= scene.background.depth_m) {
      block.Fail("depth", "depth " + Number(key.depth) +
                              " m is not in front of the background (background.depth " +
                              Number(scene.background.depth_m) + " m)");
    }
    if (!path.empty() && key.frame <= path.back().frame) {
      block.Fail("frame", "keyframe frames must increase: " + std::to_string(key.frame) +
                              " follows " + std::to_string(path.back().frame));
    }
    path.push_back(key);
  }
  return path;
}

Oscillation ReadOscillation(const ParamBlock& object) {
  const ParamBlock block = object.Child("oscillation");
  Oscillation oscillation;
  const std::vector<double> amplitude = block.GetDoubles("amplitude", {0.0, 0.0}, Coordinate(), 2);
  oscillation.amplitude_x = amplitude[0];
  oscillation.amplitude_y = amplitude[1];
  oscillation.period = block.GetDouble("period", 0.0, Positive());
  oscillation.phase = block.GetDouble("phase", 0.0, Range{0.0, 1.0, false, true});
  block.CheckNoUnknownKeys();
  if (!block.Keys().empty()) RequirePresent(block, {"period"});
  return oscillation;
}

BlobDeformation ReadBlob(const ParamBlock& object) {
  const ParamBlock block = object.Child("blob");
  BlobDeformation blob;
  blob.lobes = block.GetInt("lobes", blob.lobes, Range::Closed(kMinLobes, kMaxLobes));
  blob.amplitude =
      block.GetDouble("amplitude", blob.amplitude, Range::Closed(0, kMaxBlobAmplitude));
  blob.period = block.GetDouble("period", blob.period, Positive());
  block.CheckNoUnknownKeys();
  return blob;
}

SceneObject ReadObject(const ParamBlock& block, const Scene& scene) {
  SceneObject object;
  object.id = block.GetInt("id", 0, Range::AtLeast(1));
  object.name = block.GetString("name", "");
  object.kind = block.GetChoice("kind", object.kind, {"object", "skin"});
  object.shape = ShapeFromName(block.GetChoice("shape", "rectangle", ShapeNames()));
  const std::vector<double> size = block.GetDoubles("size", {0.2, 0.2}, Positive(), 2);
  object.width_m = size[0];
  object.height_m = size[1];
  object.colour = ReadColour(block, object.colour);
  object.texture = block.GetDouble("texture", object.texture, Range::Closed(0, 255));
  object.texture_cell_m = block.GetDouble("texture_cell", object.texture_cell_m, Positive());
  object.entry = block.GetInt("entry", 0, Range::AtLeast(0));
  object.exit = block.GetInt("exit", -1, Range::AtLeast(0));
  // Mark the nested blocks as known; they are read after the typo check of this block.
  block.Children("path");
  block.Child("oscillation");
  if (object.shape == SynthShape::kBlob || !block.Has("blob")) {
    block.Child("blob");
  } else {
    block.Fail("blob", "only valid with shape: blob (this object is a " +
                           std::string(SynthShapeName(object.shape)) + ")");
  }
  block.CheckNoUnknownKeys();
  RequirePresent(block, {"id", "size", "path"});
  if (object.name.empty()) object.name = "object" + std::to_string(object.id);

  object.path = ReadPath(block, scene);
  object.oscillation = ReadOscillation(block);
  if (object.shape == SynthShape::kBlob) object.blob = ReadBlob(block);
  if (object.entry >= scene.frames) {
    block.Fail("entry", "frame " + std::to_string(object.entry) +
                            " is after the last frame of the scene (frames: " +
                            std::to_string(scene.frames) + ")");
  }
  if (object.exit >= 0 && object.exit < object.entry) {
    block.Fail("exit", "exit " + std::to_string(object.exit) + " is before entry " +
                           std::to_string(object.entry));
  }
  return object;
}

Scene ReadScene(const ParamBlock& root) {
  const std::string& source = root.source();
  Scene scene;
  scene.source = source;
  const std::string stem = std::filesystem::path(source).stem().string();
  scene.name = root.GetString("name", stem.empty() ? scene.name : stem);
  if (scene.name.empty()) root.Fail("name", "must not be empty");
  scene.width = root.GetInt("width", scene.width, Range::Closed(kMinImageSide, kMaxImageSide));
  scene.height = root.GetInt("height", scene.height, Range::Closed(kMinImageSide, kMaxImageSide));
  if (static_cast<long>(scene.width) * scene.height > kMaxImagePixels) {
    root.Fail("height", "the image of " + std::to_string(scene.width) + " x " +
                            std::to_string(scene.height) + " pixels is larger than the " +
                            "renderer's limit of " + std::to_string(kMaxImagePixels) +
                            " pixels (3840 x 2160; docs/LIMITS.md)");
  }
  scene.frames =
      root.GetInt("frames", scene.frames, Range::Closed(1, kMaxFrameNumber + 1));
  scene.fps = root.GetDouble("fps", scene.fps, Positive());
  scene.seed = static_cast<std::uint64_t>(root.GetInt("seed", 1, Range::AtLeast(0)));

  const ParamBlock camera = root.Child("camera");
  scene.focal_px = camera.GetDouble("focal_px", scene.focal_px, Positive());
  scene.baseline_m = camera.GetDouble("baseline_m", scene.baseline_m, Positive());
  camera.CheckNoUnknownKeys();

  const ParamBlock noise = root.Child("noise");
  scene.noise_left = noise.GetDouble("left", scene.noise_left, Range::Closed(0, kMaxNoiseSigma));
  scene.noise_right = noise.GetDouble("right", scene.noise_right, Range::Closed(0, kMaxNoiseSigma));
  noise.CheckNoUnknownKeys();

  const ParamBlock background = root.Child("background");
  scene.background.depth_m = background.GetDouble("depth", scene.background.depth_m, Positive());
  scene.background.colour = ReadColour(background, scene.background.colour);
  scene.background.texture =
      background.GetDouble("texture", scene.background.texture, Range::Closed(0, 255));
  scene.background.texture_cell_m =
      background.GetDouble("texture_cell", scene.background.texture_cell_m, Positive());
  background.CheckNoUnknownKeys();

  for (const ParamBlock& block : root.Children("brightness")) {
    GainKeyframe key;
    key.frame = block.GetInt("frame", 0, Range::AtLeast(0));
    key.gain = block.GetDouble("gain", 1.0, Range::Closed(0, kMaxGain));
    block.CheckNoUnknownKeys();
    RequirePresent(block, {"frame", "gain"});
    if (!scene.brightness.empty() && key.frame <= scene.brightness.back().frame) {
      block.Fail("frame", "keyframe frames must increase: " + std::to_string(key.frame) +
                              " follows " + std::to_string(scene.brightness.back().frame));
    }
    scene.brightness.push_back(key);
  }

  const std::vector<ParamBlock> objects = root.Children("objects");
  root.CheckNoUnknownKeys();
  std::map<int, const ParamBlock*> block_of_id;
  for (const ParamBlock& block : objects) {
    SceneObject object = ReadObject(block, scene);
    const auto [it, inserted] = block_of_id.emplace(object.id, &block);
    if (!inserted) {
      block.Fail("id", "id " + std::to_string(object.id) + " is already used at " +
                           LineOf(*it->second, "id"));
    }
    scene.objects.push_back(std::move(object));
  }

  // Everything Check() rejects has been reported above with its line.
  const std::string error = scene.Check();
  ATTEND_CHECK(error.empty()) << source << ": parsed scene is invalid: " << error;
  return scene;
}

}  // namespace

Scene ParseScene(const std::string& text, const std::string& source) {
  return ReadScene(ParamBlock::Parse(text, source));
}

Scene LoadScene(const std::string& path) { return ReadScene(ParamBlock::LoadFile(path)); }

std::string Scene::Check() const {
  auto in = [](double value, double min, double max) { return value >= min && value <= max; };
  auto colour_ok = [&](const Rgb& rgb) {
    return in(rgb[0], 0, 255) && in(rgb[1], 0, 255) && in(rgb[2], 0, 255);
  };
  if (width < kMinImageSide || width > kMaxImageSide || height < kMinImageSide ||
      height > kMaxImageSide) {
    return "width and height must be in [16, 8192]";
  }
  if (static_cast<long>(width) * height > kMaxImagePixels) {
    return "width x height must be at most 3840 x 2160 pixels";
  }
  if (frames > kMaxFrameNumber + 1) return "frames must be at most 1000001";
  if (frames < 1) return "frames must be >= 1";
  if (!IsPositive(fps)) return "fps must be in (0, 1e6]";
  if (!IsPositive(focal_px)) return "camera.focal_px must be in (0, 1e6]";
  if (!IsPositive(baseline_m)) return "camera.baseline_m must be in (0, 1e6]";
  if (!in(noise_left, 0, kMaxNoiseSigma) || !in(noise_right, 0, kMaxNoiseSigma)) {
    return "noise.left and noise.right must be in [0, 100]";
  }
  if (!IsPositive(background.depth_m)) return "background.depth must be in (0, 1e6]";
  if (!colour_ok(background.colour)) return "background.colour channels must be in [0, 255]";
  if (!in(background.texture, 0, 255)) return "background.texture must be in [0, 255]";
  if (!IsPositive(background.texture_cell_m)) return "background.texture_cell must be in (0, 1e6]";
  for (size_t i = 0; i < brightness.size(); ++i) {
    if (brightness[i].frame < 0) return "brightness frames must be >= 0";
    if (!in(brightness[i].gain, 0, kMaxGain)) return "brightness gains must be in [0, 10]";
    if (i > 0 && brightness[i].frame <= brightness[i - 1].frame) {
      return "brightness keyframe frames must increase";
    }
  }
  std::map<int, int> seen;
  for (const SceneObject& o : objects) {
    const std::string what = "object " + std::to_string(o.id) + " (" + o.name + ")";
    if (o.id < 1) return what + ": id must be >= 1";
    if (!seen.emplace(o.id, 0).second) return what + ": id is used twice";
    if (o.kind != "object" && o.kind != "skin") return what + ": kind must be object or skin";
    if (!IsPositive(o.width_m) || !IsPositive(o.height_m))
      return what + ": size must be in (0, 1e6]";
    if (!colour_ok(o.colour)) return what + ": colour channels must be in [0, 255]";
    if (!in(o.texture, 0, 255)) return what + ": texture must be in [0, 255]";
    if (!IsPositive(o.texture_cell_m)) return what + ": texture_cell must be in (0, 1e6]";
    if (o.path.empty()) return what + ": path needs at least one keyframe";
    for (size_t i = 0; i < o.path.size(); ++i) {
      const PathKeyframe& key = o.path[i];
      if (key.frame < 0) return what + ": path frames must be >= 0";
      if (i > 0 && key.frame <= o.path[i - 1].frame) return what + ": path frames must increase";
      if (!IsCoordinate(key.x) || !IsCoordinate(key.y))
        return what + ": path x, y must be in [-1e6, 1e6]";
      if (!IsPositive(key.depth) || key.depth >= background.depth_m) {
        return what + ": path depth must be > 0 and in front of the background";
      }
    }
    const Oscillation& wave = o.oscillation;
    if (!(wave.period == 0.0 || IsPositive(wave.period)) || !(wave.phase >= 0 && wave.phase < 1) ||
        !IsCoordinate(wave.amplitude_x) || !IsCoordinate(wave.amplitude_y)) {
      return what +
             ": oscillation period must be 0 (none) or in (0, 1e6], phase in [0, 1), "
             "amplitudes in [-1e6, 1e6]";
    }
    if (o.shape == SynthShape::kBlob &&
        (o.blob.lobes < kMinLobes || o.blob.lobes > kMaxLobes ||
         !in(o.blob.amplitude, 0, kMaxBlobAmplitude) || !IsPositive(o.blob.period))) {
      return what + ": blob lobes must be in [2, 16], amplitude in [0, 0.6], period in (0, 1e6]";
    }
    if (o.entry < 0) return what + ": entry must be >= 0";
    if (o.exit != -1 && o.exit < o.entry) return what + ": exit must be -1 or >= entry";
  }
  return "";
}

PathKeyframe InterpolatePath(const std::vector<PathKeyframe>& path, int frame) {
  ATTEND_CHECK(!path.empty()) << "a path needs at least one keyframe";
  PathKeyframe result = path.front();
  if (frame <= path.front().frame) {
    result = path.front();
  } else if (frame >= path.back().frame) {
    result = path.back();
  } else {
    const auto next =
        std::upper_bound(path.begin(), path.end(), frame,
                         [](int f, const PathKeyframe& key) { return f < key.frame; });
    const PathKeyframe& b = *next;
    const PathKeyframe& a = *(next - 1);
    const double s = static_cast<double>(frame - a.frame) / (b.frame - a.frame);
    result.x = a.x + s * (b.x - a.x);
    result.y = a.y + s * (b.y - a.y);
    result.depth = a.depth + s * (b.depth - a.depth);
  }
  result.frame = frame;
  return result;
}

double InterpolateGain(const std::vector<GainKeyframe>& brightness, int frame) {
  if (brightness.empty()) return 1.0;
  if (frame <= brightness.front().frame) return brightness.front().gain;
  if (frame >= brightness.back().frame) return brightness.back().gain;
  const auto next = std::upper_bound(brightness.begin(), brightness.end(), frame,
                                     [](int f, const GainKeyframe& key) { return f < key.frame; });
  const GainKeyframe& b = *next;
  const GainKeyframe& a = *(next - 1);
  const double s = static_cast<double>(frame - a.frame) / (b.frame - a.frame);
  return a.gain + s * (b.gain - a.gain);
}

}  // namespace attend
