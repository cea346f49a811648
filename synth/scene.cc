#include "synth/scene.h"

#include <algorithm>
#include <filesystem>
#include <initializer_list>
#include <map>
#include <sstream>
#include <string_view>

#include "config/param_block.h"
#include "config/read_fields.h"
#include "synth/scene_fields.h"
#include "util/enum_table.h"
#include "util/error.h"
#include "util/limits.h"

namespace attend {

namespace {

constexpr EnumTable<SynthShape, 4> kSynthShapes = {{{{SynthShape::kRectangle, "rectangle"},
                                                     {SynthShape::kEllipse, "ellipse"},
                                                     {SynthShape::kTriangle, "triangle"},
                                                     {SynthShape::kBlob, "blob"}}}};

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
using scene_fields::Coordinate;
using scene_fields::IsCoordinate;
using scene_fields::IsPositive;
using scene_fields::kLargest;
using scene_fields::Positive;

const std::vector<std::string>& Kinds() {
  static const std::vector<std::string> kinds = {"object", "skin", "car", "person", "cyclist"};
  return kinds;
}

using scene_fields::ColourMember;

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

// The line of a block's key, for messages that point at an earlier definition.
std::string LineOf(const ParamBlock& block, const std::string& key) {
  const std::string where = block.Where(key);
  const size_t colon = where.rfind(':');
  return colon == std::string::npos ? where : "line " + where.substr(colon + 1);
}

std::vector<PathKeyframe> ReadPath(const ParamBlock& object, const Scene& scene) {
  std::vector<PathKeyframe> path = ReadList(
      object, "path", PathKeyframe::Fields(), PathKeyframe(),
      [&](const ParamBlock& block, const PathKeyframe& key, const std::vector<PathKeyframe>& before) {
        RequirePresent(block, {"frame", "x", "y", "depth"});
        if (key.depth >= scene.background.depth_m) {
          block.Fail("depth", "depth " + Number(key.depth) +
                                  " m is not in front of the background (background.depth " +
                                  Number(scene.background.depth_m) + " m)");
        }
        if (!before.empty() && key.frame <= before.back().frame) {
          block.Fail("frame", "keyframe frames must increase: " + std::to_string(key.frame) +
                                  " follows " + std::to_string(before.back().frame));
        }
      });
  if (path.empty()) object.Fail("path", "needs at least one keyframe {frame, x, y, depth}");
  return path;
}

std::vector<GroundKeyframe> ReadGroundPath(const ParamBlock& object) {
  std::vector<GroundKeyframe> path = ReadList(
      object, "ground_path", GroundKeyframe::Fields(), GroundKeyframe(),
      [&](const ParamBlock& block, const GroundKeyframe& key,
          const std::vector<GroundKeyframe>& before) {
        RequirePresent(block, {"frame", "lateral", "distance"});
        if (!before.empty() && key.frame <= before.back().frame) {
          block.Fail("frame", "keyframe frames must increase: " + std::to_string(key.frame) +
                                  " follows " + std::to_string(before.back().frame));
        }
      });
  if (path.empty()) {
    object.Fail("ground_path", "needs at least one keyframe {frame, lateral, distance}");
  }
  return path;
}

// A street object stands on the ground along a ground_path; the keys that place an object in
// pixels (path, oscillation) and the blob, whose outline has no base, belong to the other mode.
void ReadStreetPlacement(const ParamBlock& block, SceneObject* object) {
  for (const char* key : {"path", "oscillation"}) {
    if (block.Has(key)) block.Fail(key, "not used in a street scene (objects use ground_path)");
  }
  if (object->shape == SynthShape::kBlob) {
    block.Fail("shape", "blob is not available in a street scene");
  }
  RequirePresent(block, {"ground_path"});
  object->ground_path = ReadGroundPath(block);
}

SceneObject ReadObject(const ParamBlock& block, const Scene& scene) {
  SceneObject object;
  object.name = "";  // unnamed: "object<id>" below
  ReadFields(block, SceneObject::Fields(), &object);
  // Mark the nested blocks as known; they are read after the typo check of this block.
  block.Children("path");
  if (scene.street.has_value()) {
    block.Children("ground_path");
  } else if (block.Has("ground_path")) {
    block.Fail("ground_path", "only valid in a street scene (a scene with a street block)");
  }
  block.Child("oscillation");
  if (object.shape == SynthShape::kBlob || !block.Has("blob")) {
    block.Child("blob");
  } else {
    block.Fail("blob", "only valid with shape: blob (this object is a " +
                           std::string(SynthShapeName(object.shape)) + ")");
  }
  block.CheckNoUnknownKeys();
  RequirePresent(block, {"id", "size"});
  if (object.name.empty()) object.name = "object" + std::to_string(object.id);

  if (scene.street.has_value()) {
    ReadStreetPlacement(block, &object);
  } else {
    RequirePresent(block, {"path"});
    object.path = ReadPath(block, scene);
    const ParamBlock oscillation =
        ReadSection(block, "oscillation", Oscillation::Fields(), &object.oscillation);
    if (!oscillation.Keys().empty()) RequirePresent(oscillation, {"period"});
    if (object.shape == SynthShape::kBlob) {
      ReadSection(block, "blob", BlobDeformation::Fields(), &object.blob);
    }
  }
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

// The `street` block and its ground, sky and backdrop maps.
void ReadStreet(const ParamBlock& root, Scene* scene) {
  StreetSetting street;
  const ParamBlock block = root.Child("street");
  for (const char* key : {"ground", "sky", "backdrop"}) block.Child(key);
  block.CheckNoUnknownKeys();
  ReadSection(block, "ground", StreetGround::Fields(), &street.ground);
  ReadSection(block, "sky", StreetSky::Fields(), &street.sky);
  const ParamBlock backdrop =
      ReadSection(block, "backdrop", StreetBackdrop::Fields(), &street.backdrop);
  if (street.backdrop.max_height_m < street.backdrop.min_height_m) {
    backdrop.Fail("max_height", "is below min_height");
  }
  if (root.Has("background")) {
    root.Fail("background", "not used in a street scene (street.backdrop is its far wall)");
  }
  scene->street = street;
}

Scene ReadScene(const ParamBlock& root) {
  const std::string& source = root.source();
  Scene scene;
  scene.source = source;
  const std::string stem = std::filesystem::path(source).stem().string();
  if (!stem.empty()) scene.name = stem;
  ReadFields(root, Scene::Fields(), &scene);
  if (scene.name.empty()) root.Fail("name", "must not be empty");
  if (static_cast<long>(scene.width) * scene.height > kMaxImagePixels) {
    root.Fail("height", "the image of " + std::to_string(scene.width) + " x " +
                            std::to_string(scene.height) + " pixels is larger than the " +
                            "renderer's limit of " + std::to_string(kMaxImagePixels) +
                            " pixels (3840 x 2160; docs/LIMITS.md)");
  }
  const ParamBlock camera = ReadSection(root, "camera", Scene::CameraFields(), &scene);
  ReadSection(root, "noise", Scene::NoiseFields(), &scene);
  if (root.Has("street")) {
    ReadStreet(root, &scene);
  } else {
    for (const char* key : {"height_m", "pitch_deg", "speed_mps"}) {
      if (camera.Has(key)) camera.Fail(key, "only valid in a street scene (add a street block)");
    }
  }
  ReadSection(root, "background", SceneBackground::Fields(), &scene.background);
  scene.brightness = ReadList(
      root, "brightness", GainKeyframe::Fields(), GainKeyframe(),
      [](const ParamBlock& block, const GainKeyframe& key, const std::vector<GainKeyframe>& before) {
        RequirePresent(block, {"frame", "gain"});
        if (!before.empty() && key.frame <= before.back().frame) {
          block.Fail("frame", "keyframe frames must increase: " + std::to_string(key.frame) +
                                  " follows " + std::to_string(before.back().frame));
        }
      });

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

// The street camera's keys and the street block (Check() goes on with the rest).
std::string CheckStreet(const Scene& scene) {
  if (!IsPositive(scene.camera_height_m)) return "camera.height_m must be in (0, 1e6]";
  if (!(scene.pitch_deg >= -30 && scene.pitch_deg <= 30)) {
    return "camera.pitch_deg must be in [-30, 30]";
  }
  if (!(scene.speed_mps >= 0 && scene.speed_mps <= 100)) return "camera.speed_mps must be in [0, 100]";
  if (!scene.street.has_value()) return "";
  const StreetSetting& street = *scene.street;
  std::string error = CheckFieldRanges(street.ground, StreetGround::Fields());
  if (!error.empty()) return "street.ground." + error;
  error = CheckFieldRanges(street.sky, StreetSky::Fields());
  if (!error.empty()) return "street.sky." + error;
  error = CheckFieldRanges(street.backdrop, StreetBackdrop::Fields());
  if (!error.empty()) return "street.backdrop." + error;
  if (street.backdrop.max_height_m < street.backdrop.min_height_m) {
    return "street.backdrop.max_height must be >= min_height";
  }
  return "";
}

// The checks of a street object's placement (Check() continues with the next object after).
std::string CheckGroundPath(const SceneObject& o) {
  if (o.ground_path.empty()) return "ground_path needs at least one keyframe";
  if (!o.path.empty()) return "path is not used in a street scene";
  if (o.shape == SynthShape::kBlob) return "blob is not available in a street scene";
  if (o.entry < 0) return "entry must be >= 0";
  if (o.exit != -1 && o.exit < o.entry) return "exit must be -1 or >= entry";
  for (size_t i = 0; i < o.ground_path.size(); ++i) {
    const GroundKeyframe& key = o.ground_path[i];
    if (key.frame < 0) return "ground_path frames must be >= 0";
    if (i > 0 && key.frame <= o.ground_path[i - 1].frame) {
      return "ground_path frames must increase";
    }
    if (!IsCoordinate(key.lateral) || !IsCoordinate(key.distance)) {
      return "ground_path lateral, distance must be in [-1e6, 1e6]";
    }
  }
  return "";
}

}  // namespace

const char* SynthShapeName(SynthShape shape) {
  const char* name = kSynthShapes.Name(shape);
  return std::string_view(name) == "?" ? "unknown" : name;
}

const OptionFields<PathKeyframe>& PathKeyframe::Fields() {
  using K = PathKeyframe;
  static const OptionFields<K> fields = {
      {"frame", &K::frame, Range::AtLeast(0), "the frame of the keyframe"},
      {"x", &K::x, Coordinate(), "the centre's column in the left image, px"},
      {"y", &K::y, Coordinate(), "the centre's row, px"},
      {"depth", &K::depth, Positive(), "its depth, m, in front of the background"}};
  return fields;
}

const OptionFields<GainKeyframe>& GainKeyframe::Fields() {
  static const OptionFields<GainKeyframe> fields = {
      {"frame", &GainKeyframe::frame, Range::AtLeast(0), "the frame of the keyframe"},
      {"gain", &GainKeyframe::gain, Range::Closed(0, kMaxGain),
       "the gain on every surface colour"}};
  return fields;
}

const OptionFields<Oscillation>& Oscillation::Fields() {
  using O = Oscillation;
  static const OptionFields<O> fields = {
      {"amplitude",
       NumbersMember<O>{[](const O& o) { return std::vector<double>{o.amplitude_x, o.amplitude_y}; },
                        [](O* o, const std::vector<double>& v) {
                          o->amplitude_x = v[0];
                          o->amplitude_y = v[1];
                        },
                        2},
       Coordinate(), "[x, y] amplitude of the offset, px"},
      {"period", &O::period, Positive(), "frames of one cycle (required with the block)"},
      {"phase", &O::phase, Range{0.0, 1.0, false, true}, "fraction of a period at frame 0"}};
  return fields;
}

const OptionFields<BlobDeformation>& BlobDeformation::Fields() {
  using B = BlobDeformation;
  static const OptionFields<B> fields = {
      {"lobes", &B::lobes, Range::Closed(kMinLobes, kMaxLobes), "lobes of the first wave"},
      {"amplitude", &B::amplitude, Range::Closed(0, kMaxBlobAmplitude),
       "the radius varies by at most this share"},
      {"period", &B::period, Positive(), "frames for one cycle of the first wave"}};
  return fields;
}

const OptionFields<SceneObject>& SceneObject::Fields() {
  using O = SceneObject;
  static const OptionFields<O> fields = {
      {"id", &O::id, Range::AtLeast(1), "the object's id in the id maps, unique (required)"},
      {"name", &O::name, "for people reading the scene; default object<id>"},
      {"kind", &O::kind, "the ground-truth kind", &Kinds},
      {"shape", EnumField<&O::shape, kSynthShapes>(), "the outline"},
      {"size",
       NumbersMember<O>{[](const O& o) { return std::vector<double>{o.width_m, o.height_m}; },
                        [](O* o, const std::vector<double>& v) {
                          o->width_m = v[0];
                          o->height_m = v[1];
                        },
                        2},
       Positive(), "[width, height], m (required)"},
      {"colour", ColourMember<O, &O::colour>(), Range::Closed(0, 255), "[r, g, b]"},
      {"texture", &O::texture, Range::Closed(0, 255), "texture amplitude, grey levels"},
      {"texture_cell", &O::texture_cell_m, Positive(), "texture lattice spacing, m"},
      {"entry", &O::entry, Range::AtLeast(0), "first frame present"},
      {"exit", &O::exit, Range::AtLeast(0), "last frame present; absent: to the end"}};
  return fields;
}

const OptionFields<SceneBackground>& SceneBackground::Fields() {
  using B = SceneBackground;
  static const OptionFields<B> fields = {
      {"depth", &B::depth_m, Positive(), "depth of the background plane, m"},
      {"colour", ColourMember<B, &B::colour>(), Range::Closed(0, 255), "[r, g, b]"},
      {"texture", &B::texture, Range::Closed(0, 255), "texture amplitude, grey levels"},
      {"texture_cell", &B::texture_cell_m, Positive(), "texture lattice spacing, m"}};
  return fields;
}

const OptionFields<Scene>& Scene::Fields() {
  static const OptionFields<Scene> fields = {
      {"name", &Scene::name, "the sequence's name; default the file's stem"},
      {"width", &Scene::width, Range::Closed(kMinImageSide, kMaxImageSide), "image width, px"},
      {"height", &Scene::height, Range::Closed(kMinImageSide, kMaxImageSide), "image height, px"},
      {"frames", &Scene::frames, Range::Closed(1, kMaxFrameNumber + 1), "frames rendered"},
      {"fps", &Scene::fps, Positive(), "frames a second"},
      // Read as before through an int's range: seeds of up to 2^31 - 1.
      {"seed", &Scene::seed, Range::Closed(0, 2147483647),
       "textures, blob phases and noise derive from it"}};
  return fields;
}

const OptionFields<Scene>& Scene::CameraFields() {
  static const OptionFields<Scene> fields = {
      {"focal_px", &Scene::focal_px, Positive(), "focal length, px"},
      {"baseline_m", &Scene::baseline_m, Positive(), "stereo baseline, m"},
      {"height_m", &Scene::camera_height_m, Positive(),
       "street scenes: the camera's height above the ground, m"},
      {"pitch_deg", &Scene::pitch_deg, Range::Closed(-30, 30),
       "street scenes: pitch, degrees, positive looks down"},
      {"speed_mps", &Scene::speed_mps, Range::Closed(0, 100),
       "street scenes: forward speed, m/s"}};
  return fields;
}

const OptionFields<Scene>& Scene::NoiseFields() {
  static const OptionFields<Scene> fields = {
      {"left", &Scene::noise_left, Range::Closed(0, kMaxNoiseSigma),
       "Gaussian noise sigma of the left view, grey levels"},
      {"right", &Scene::noise_right, Range::Closed(0, kMaxNoiseSigma), "same, right view"}};
  return fields;
}

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
  const std::string street_error = CheckStreet(*this);
  if (!street_error.empty()) return street_error;
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
    if (std::find(Kinds().begin(), Kinds().end(), o.kind) == Kinds().end()) {
      return what + ": kind must be object, skin, car, person or cyclist";
    }
    if (!IsPositive(o.width_m) || !IsPositive(o.height_m))
      return what + ": size must be in (0, 1e6]";
    if (!colour_ok(o.colour)) return what + ": colour channels must be in [0, 255]";
    if (!in(o.texture, 0, 255)) return what + ": texture must be in [0, 255]";
    if (!IsPositive(o.texture_cell_m)) return what + ": texture_cell must be in (0, 1e6]";
    if (street.has_value()) {
      const std::string error = CheckGroundPath(o);
      if (!error.empty()) return what + ": " + error;
      continue;
    }
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
