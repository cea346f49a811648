#include "synth/renderer.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "synth/sampling.h"
#include "synth/street_renderer.h"
#include "util/error.h"

namespace attend {

namespace {

using synth_sampling::GaussianSource;
using synth_sampling::kNoiseDomain;
using synth_sampling::kSurfaceDomain;
using synth_sampling::kTwoPi;
using synth_sampling::Mix;
using synth_sampling::Texture;
using synth_sampling::ToByte;
using synth_sampling::UnitInterval;

// The first blob wave advances once per `period`; the second runs the other way at a
// different speed, so the outline deforms instead of rotating rigidly.
constexpr double kSecondWaveSpeed = 0.77;
constexpr double kFirstWaveWeight = 0.6;
constexpr double kSecondWaveWeight = 0.4;

// One surface at one frame, in left-image pixels.
struct Surface {
  int id = 0;  // 0: the background
  SynthShape shape = SynthShape::kRectangle;
  double cx = 0.0, cy = 0.0;              // centre (texture origin)
  double half_w = 1.0, half_h = 1.0;      // half size of the base shape
  double extent_x = 1.0, extent_y = 1.0;  // half size of the bounding box
  double depth = 1.0;
  double disparity = 0.0;
  double lattice_per_px = 1.0;  // texture lattice units per pixel
  std::uint64_t key = 0;
  Rgb colour = {0, 0, 0};
  double texture = 0.0;
  // Blob only.
  int lobes = 0;
  double amplitude = 0.0;
  double wave1 = 0.0, wave2 = 0.0;  // phases at this frame, radians

  // Whether the point at (nx, ny), in units of the half size from the centre, is covered.
  // Edges are half-open so that a shape of width w px at integer alignment covers w pixels.
  bool Covers(double nx, double ny) const {
    switch (shape) {
      case SynthShape::kRectangle:
        return nx >= -1.0 && nx < 1.0 && ny >= -1.0 && ny < 1.0;
      case SynthShape::kEllipse:
        return nx * nx + ny * ny < 1.0;
      case SynthShape::kTriangle:  // apex at the top, base at the bottom
        return ny < 1.0 && 2.0 * std::abs(nx) < ny + 1.0;
      case SynthShape::kBlob: {
        const double rho2 = nx * nx + ny * ny;
        const double inner = 1.0 - amplitude;
        const double outer = 1.0 + amplitude;
        if (rho2 < inner * inner) return true;
        if (rho2 >= outer * outer) return false;
        const double theta = std::atan2(ny, nx);
        const double g = kFirstWaveWeight * std::sin(lobes * theta + wave1) +
                         kSecondWaveWeight * std::sin((lobes + 1) * theta + wave2);
        const double radius = 1.0 + amplitude * g;
        return rho2 < radius * radius;
      }
    }
    return false;
  }

  // Whether the pixel whose centre is at left-image coordinates (x, y) is covered.
  bool CoversPixel(double x, double y) const {
    return Covers((x - cx) / half_w, (y - cy) / half_h);
  }
};

// The inclusive range of integer coordinates in [centre - extent, centre + extent], clamped so
// that an object projected absurdly large (tiny depth, huge size) cannot overflow an int.
void LatticeRange(double centre, double extent, int* first, int* last) {
  constexpr double kLimit = 1 << 30;
  *first = static_cast<int>(std::clamp(std::ceil(centre - extent), -kLimit, kLimit));
  *last = static_cast<int>(std::clamp(std::floor(centre + extent), -kLimit, kLimit));
}

// Which surface covers each pixel of one view: the index into `surfaces` (sorted nearest
// first), or -1 for the background. A pixel of the right view at x shows the surface point
// that the left view shows at x + disparity.
std::vector<int> Coverage(const std::vector<Surface>& surfaces, bool right, int width, int height) {
  std::vector<int> owner(static_cast<size_t>(width) * height, -1);
  for (size_t k = 0; k < surfaces.size(); ++k) {
    const Surface& s = surfaces[k];
    const double shift = right ? s.disparity : 0.0;
    int x0, x1, y0, y1;
    LatticeRange(s.cx - shift, s.extent_x, &x0, &x1);
    LatticeRange(s.cy, s.extent_y, &y0, &y1);
    x0 = std::max(x0, 0);
    y0 = std::max(y0, 0);
    x1 = std::min(x1, width - 1);
    y1 = std::min(y1, height - 1);
    for (int y = y0; y <= y1; ++y) {
      int* row = owner.data() + static_cast<size_t>(y) * width;
      for (int x = x0; x <= x1; ++x) {
        // Nearer surfaces came first and keep their pixels.
        if (row[x] < 0 && s.CoversPixel(x + shift, y)) row[x] = static_cast<int>(k);
      }
    }
  }
  return owner;
}

// Shades one view from its coverage, adds noise, and fills the id map (and the disparity map
// for the left view).
void ShadeView(const std::vector<Surface>& surfaces, const Surface& background,
               const std::vector<int>& owner, bool right, double gain, double sigma,
               std::uint64_t noise_seed, cv::Mat* image, cv::Mat* ids, cv::Mat* disparity) {
  const int width = image->cols;
  const int height = image->rows;
  GaussianSource noise(noise_seed);
  for (int y = 0; y < height; ++y) {
    cv::Vec3b* pixels = image->ptr<cv::Vec3b>(y);
    int* id_row = ids->ptr<int>(y);
    float* disparity_row = disparity != nullptr ? disparity->ptr<float>(y) : nullptr;
    for (int x = 0; x < width; ++x) {
      const int k = owner[static_cast<size_t>(y) * width + x];
      const Surface& s = k >= 0 ? surfaces[k] : background;
      const double x_left = x + (right ? s.disparity : 0.0);
      double texture = 0.0;
      if (s.texture > 0.0) {
        texture = s.texture *
                  Texture(s.key, (x_left - s.cx) * s.lattice_per_px, (y - s.cy) * s.lattice_per_px);
      }
      // Output is BGR; colours are RGB. Noise is drawn in B, G, R order for every pixel.
      for (int c = 0; c < 3; ++c) {
        double value = gain * (s.colour[2 - c] + texture);
        if (sigma > 0.0) value += sigma * noise.Next();
        pixels[x][c] = ToByte(value);
      }
      id_row[x] = s.id;
      if (disparity_row != nullptr) disparity_row[x] = static_cast<float>(s.disparity);
    }
  }
}

// Pixel centres covered by the whole projected surface, inside the image or not. Counted
// exactly up to kMaxCountedPixels of bounding box; beyond that the shape's area stands in for
// the count (they differ by about the perimeter), so a huge object costs no time.
double ProjectedPixels(const Surface& s) {
  constexpr double kMaxCountedPixels = 1 << 22;
  int x0, x1, y0, y1;
  LatticeRange(s.cx, s.extent_x, &x0, &x1);
  LatticeRange(s.cy, s.extent_y, &y0, &y1);
  const double box = (static_cast<double>(x1) - x0 + 1) * (static_cast<double>(y1) - y0 + 1);
  if (box > kMaxCountedPixels) {
    const double quarter = s.half_w * s.half_h;
    switch (s.shape) {
      case SynthShape::kRectangle:
        return 4.0 * quarter;
      case SynthShape::kEllipse:
        return std::numbers::pi * quarter;
      case SynthShape::kTriangle:
        return 2.0 * quarter;
      case SynthShape::kBlob:  // the mean of (1 + a g)^2 over theta is 1 + a^2 (0.6^2 + 0.4^2) / 2
        return std::numbers::pi * quarter *
               (1.0 +
                s.amplitude * s.amplitude *
                    (kFirstWaveWeight * kFirstWaveWeight + kSecondWaveWeight * kSecondWaveWeight) /
                    2.0);
    }
  }
  long long count = 0;
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) count += s.CoversPixel(x, y) ? 1 : 0;
  }
  return static_cast<double>(count);
}

// The ground truth of the left view from its coverage (`owner`: the surface of each pixel, -1
// none): each surface's visible box and the share of it that is visible.
std::vector<GtObject> GroundTruth(const Scene& scene, int frame,
                                  const std::vector<Surface>& surfaces,
                                  const std::vector<int>& left_owner, int width, int height) {
  std::vector<GtObject> objects;
  struct Visible {
    long long pixels = 0;
    int x0 = 0, y0 = 0, x1 = -1, y1 = -1;
  };
  std::vector<Visible> visible(surfaces.size());
  for (int y = 0; y < height; ++y) {
    const int* row = left_owner.data() + static_cast<size_t>(y) * width;
    for (int x = 0; x < width; ++x) {
      if (row[x] < 0) continue;
      Visible& v = visible[row[x]];
      if (v.pixels == 0) {
        v.x0 = v.x1 = x;
        v.y0 = v.y1 = y;
      }
      ++v.pixels;
      v.x0 = std::min(v.x0, x);
      v.x1 = std::max(v.x1, x);
      v.y1 = y;
    }
  }
  for (size_t k = 0; k < surfaces.size(); ++k) {
    const Surface& s = surfaces[k];
    GtObject gt;
    gt.frame = frame;
    gt.id = s.id;
    gt.disparity = s.disparity;
    const auto it = std::find_if(scene.objects.begin(), scene.objects.end(),
                                 [&](const SceneObject& o) { return o.id == s.id; });
    gt.kind = it->kind;
    const Visible& v = visible[k];
    if (v.pixels > 0) {
      gt.box = cv::Rect2d(v.x0, v.y0, v.x1 - v.x0 + 1, v.y1 - v.y0 + 1);
      gt.visible_fraction = std::min(1.0, static_cast<double>(v.pixels) / ProjectedPixels(s));
    }
    objects.push_back(gt);
  }
  return objects;
}

// Object `o` of `scene` as the surface it is at `frame` (present in it): its pose, projected
// size, blob waves and texture. `key` and `phases` are its texture key and blob phases.
Surface ObjectSurface(const Scene& scene, const SceneObject& o, int frame, std::uint64_t key,
                      const std::array<double, 2>& phases) {
  const double focal_baseline = scene.focal_px * scene.baseline_m;
  const PathKeyframe pose = InterpolatePath(o.path, frame);
  Surface s;
  s.id = o.id;
  s.shape = o.shape;
  s.cx = pose.x;
  s.cy = pose.y;
  if (o.oscillation.period > 0.0) {
    const double wave = std::sin(kTwoPi * (frame / o.oscillation.period + o.oscillation.phase));
    s.cx += o.oscillation.amplitude_x * wave;
    s.cy += o.oscillation.amplitude_y * wave;
  }
  s.depth = pose.depth;
  s.disparity = focal_baseline / pose.depth;
  // Projected size f * size / Z: an approaching object grows.
  s.half_w = 0.5 * scene.focal_px * o.width_m / pose.depth;
  s.half_h = 0.5 * scene.focal_px * o.height_m / pose.depth;
  s.extent_x = s.half_w;
  s.extent_y = s.half_h;
  if (o.shape == SynthShape::kBlob) {
    s.lobes = o.blob.lobes;
    s.amplitude = o.blob.amplitude;
    const double cycle = kTwoPi * frame / o.blob.period;
    s.wave1 = phases[0] + cycle;
    s.wave2 = phases[1] - kSecondWaveSpeed * cycle;
    s.extent_x *= 1.0 + s.amplitude;
    s.extent_y *= 1.0 + s.amplitude;
  }
  s.lattice_per_px = pose.depth / (scene.focal_px * o.texture_cell_m);
  s.key = key;
  s.colour = o.colour;
  s.texture = o.texture;
  return s;
}

}  // namespace

SceneRenderer::SceneRenderer(Scene scene) : scene_(std::move(scene)) {
  const std::string error = scene_.Check();
  if (!error.empty()) {
    throw ConfigError((scene_.source.empty() ? scene_.name : scene_.source) + ": " + error);
  }
  if (scene_.street.has_value()) {
    street_ = std::make_shared<const StreetRenderer>(scene_);
    return;
  }
  background_key_ = Mix(scene_.seed, kSurfaceDomain);
  for (const SceneObject& object : scene_.objects) {
    // Keyed by id, so adding an object leaves the others' textures and blobs unchanged.
    std::mt19937_64 engine(
        Mix(Mix(scene_.seed, kSurfaceDomain), static_cast<std::uint64_t>(object.id)));
    texture_keys_.push_back(engine());
    const double phase1 = kTwoPi * UnitInterval(engine());
    const double phase2 = kTwoPi * UnitInterval(engine());
    blob_phases_.push_back({phase1, phase2});
  }
}

RenderedFrame SceneRenderer::Render(int frame) const {
  ATTEND_CHECK(frame >= 0) << "frame " << frame;
  if (street_) return street_->Render(frame);
  const int width = scene_.width;
  const int height = scene_.height;
  const double focal_baseline = scene_.focal_px * scene_.baseline_m;

  Surface background;
  background.id = 0;
  background.depth = scene_.background.depth_m;
  background.disparity = focal_baseline / background.depth;
  background.lattice_per_px =
      background.depth / (scene_.focal_px * scene_.background.texture_cell_m);
  background.key = background_key_;
  background.colour = scene_.background.colour;
  background.texture = scene_.background.texture;

  // Surfaces present in this frame, with their scene index.
  std::vector<Surface> surfaces;
  for (size_t i = 0; i < scene_.objects.size(); ++i) {
    const SceneObject& o = scene_.objects[i];
    if (frame < o.entry || (o.exit >= 0 && frame > o.exit)) continue;
    surfaces.push_back(ObjectSurface(scene_, o, frame, texture_keys_[i], blob_phases_[i]));
  }
  // Nearest first; at equal depth the object listed first in the scene is in front.
  std::stable_sort(surfaces.begin(), surfaces.end(),
                   [](const Surface& a, const Surface& b) { return a.depth < b.depth; });

  RenderedFrame out;
  out.frame = frame;
  out.left.create(height, width, CV_8UC3);
  out.right.create(height, width, CV_8UC3);
  out.disparity.create(height, width, CV_32FC1);
  out.left_ids.create(height, width, CV_32SC1);
  out.right_ids.create(height, width, CV_32SC1);

  const double gain = InterpolateGain(scene_.brightness, frame);
  const std::uint64_t frame_seed =
      Mix(Mix(scene_.seed, kNoiseDomain), static_cast<std::uint64_t>(frame));
  const std::vector<int> left_owner = Coverage(surfaces, false, width, height);
  const std::vector<int> right_owner = Coverage(surfaces, true, width, height);
  ShadeView(surfaces, background, left_owner, false, gain, scene_.noise_left, Mix(frame_seed, 0),
            &out.left, &out.left_ids, &out.disparity);
  ShadeView(surfaces, background, right_owner, true, gain, scene_.noise_right, Mix(frame_seed, 1),
            &out.right, &out.right_ids, nullptr);

  out.objects = GroundTruth(scene_, frame, surfaces, left_owner, width, height);
  std::sort(out.objects.begin(), out.objects.end(),
            [](const GtObject& a, const GtObject& b) { return a.id < b.id; });
  return out;
}

}  // namespace attend
