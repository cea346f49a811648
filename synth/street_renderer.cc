#include "synth/street_renderer.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <utility>

#include "synth/sampling.h"
#include "util/error.h"

namespace attend {

namespace {

using synth_sampling::GaussianSource;
using synth_sampling::Mix;
using synth_sampling::Texture;
using synth_sampling::ToByte;
using synth_sampling::UnitInterval;

constexpr std::uint64_t kGroundDomain = 0x243f6a8885a308d3ULL;
constexpr std::uint64_t kSkyDomain = 0x13198a2e03707344ULL;
constexpr std::uint64_t kBackdropDomain = 0xa4093822299f31d0ULL;
constexpr double kDegree = std::numbers::pi / 180.0;
constexpr double kInfinity = std::numeric_limits<double>::infinity();
// Windows of the facades: a grid of this period (metres) across and up, each window this
// share of its cell, the lowest row above a shop-front storey.
constexpr double kWindowPeriodX = 3.0;
constexpr double kWindowPeriodY = 3.2;
constexpr double kWindowShare = 0.45;
constexpr double kGroundFloorM = 3.0;

// The pinhole camera of the left view and its pose: world X to the right, Y down, Z along the
// road, the ground at Y = 0; the camera at (0, -height, distance), pitched down by `pitch`
// about its x axis. The right camera is the left one moved by the baseline along X.
struct Camera {
  double f = 1.0, cx = 0.0, cy = 0.0;
  double height = 1.5, distance = 0.0;
  double cos_pitch = 1.0, sin_pitch = 0.0;

  // The world direction of the ray through pixel (x, y). Its camera-frame z is 1, so a point
  // at ray parameter t has depth Z = t, and disparity f B / t.
  cv::Vec3d Ray(double x, double y) const {
    const double dx = (x - cx) / f;
    const double dy = (y - cy) / f;
    return {dx, cos_pitch * dy + sin_pitch, -sin_pitch * dy + cos_pitch};
  }
  // The camera-frame depth of a world point at height Y and distance Z (any X).
  double DepthOf(double y, double z) const {
    return sin_pitch * (y + height) + cos_pitch * (z - distance);
  }
  // The left-image pixel of world point (X, Y, Z), in front of the camera.
  cv::Point2d Project(double x, double y, double z) const {
    const double py = y + height;
    const double pz = z - distance;
    const double depth = sin_pitch * py + cos_pitch * pz;
    const double camera_y = cos_pitch * py - sin_pitch * pz;
    return {cx + f * x / depth, cy + f * camera_y / depth};
  }
};

Camera MakeCamera(const Scene& scene, int frame) {
  Camera camera;
  camera.f = scene.focal_px;
  camera.cx = 0.5 * (scene.width - 1);
  camera.cy = 0.5 * (scene.height - 1);
  camera.height = scene.camera_height_m;
  camera.distance = CameraDistance(scene, frame);
  camera.cos_pitch = std::cos(scene.pitch_deg * kDegree);
  camera.sin_pitch = std::sin(scene.pitch_deg * kDegree);
  return camera;
}

// An upright object at one frame: a vertical billboard facing along the road, its base on the
// ground, spanning lateral +- half_width and heights 0 to `height` (Y from -height to 0).
struct Billboard {
  const SceneObject* object = nullptr;
  std::uint64_t key = 0;
  double lateral = 0.0, distance = 0.0;
  double half_width = 0.5, height = 1.0;
  double centre_depth = 1.0;  // camera-frame depth of its centre
};

// Whether the billboard's shape covers the point at (nx, ny), normalised by the half size from
// its centre (docs/SYNTH.md, "Geometry": the same outlines as the other objects).
bool Covers(SynthShape shape, double nx, double ny) {
  switch (shape) {
    case SynthShape::kEllipse:
      return nx * nx + ny * ny < 1.0;
    case SynthShape::kTriangle:
      return ny < 1.0 && 2.0 * std::abs(nx) < ny + 1.0;
    default:
      return nx >= -1.0 && nx < 1.0 && ny >= -1.0 && ny < 1.0;
  }
}

// What a ray meets first: its parameter (= depth) and class, and the billboard's index.
struct RayHit {
  double t = kInfinity;
  PixelClass what = PixelClass::kSky;
  int billboard = -1;
};

double FacadeHeight(const StreetBackdrop& backdrop, std::uint64_t key, std::int64_t facade) {
  const double u = UnitInterval(Mix(key, static_cast<std::uint64_t>(facade)));
  return backdrop.min_height_m + u * (backdrop.max_height_m - backdrop.min_height_m);
}

// The nearest surface along the ray from (x0, -height, distance) in direction `d`.
RayHit Cast(const Camera& camera, const StreetSetting& street, std::uint64_t backdrop_key,
            const std::vector<Billboard>& billboards, double x0, const cv::Vec3d& d) {
  RayHit hit;
  if (d[1] > 0.0) {
    hit.t = camera.height / d[1];
    hit.what = PixelClass::kGround;
  }
  if (d[2] <= 0.0) return hit;
  const StreetBackdrop& backdrop = street.backdrop;
  if (backdrop.distance_m > 0.0) {
    const double t = (backdrop.distance_m - camera.distance) / d[2];
    if (t > 0.0 && t < hit.t) {
      const double x = x0 + t * d[0];
      const double y = -camera.height + t * d[1];
      const auto facade = static_cast<std::int64_t>(std::floor(x / backdrop.facade_width_m));
      if (-y <= FacadeHeight(backdrop, backdrop_key, facade)) {
        hit.t = t;
        hit.what = PixelClass::kOther;
      }
    }
  }
  for (size_t k = 0; k < billboards.size(); ++k) {
    const Billboard& b = billboards[k];
    const double t = (b.distance - camera.distance) / d[2];
    if (t <= 0.0 || t >= hit.t) continue;  // nearer first: at equal depth the first listed wins
    const double nx = (x0 + t * d[0] - b.lateral) / b.half_width;
    const double ny = (-camera.height + t * d[1] + 0.5 * b.height) / (0.5 * b.height);
    if (Covers(b.object->shape, nx, ny)) {
      hit.t = t;
      hit.what = PixelClass::kObject;
      hit.billboard = static_cast<int>(k);
    }
  }
  return hit;
}

// A surface point's colour before gain and noise: its colour plus a texture value added to
// every channel (so texture changes brightness, not hue).
struct Shade {
  Rgb colour = {0, 0, 0};
  double texture = 0.0;
};

Shade GroundShade(const StreetGround& ground, std::uint64_t key, const Camera& camera, double x,
                  double z, double t) {
  Shade shade;
  const double half_road = 0.5 * ground.road_width_m;
  shade.colour = std::abs(x) <= half_road ? ground.colour : ground.verge_colour;
  if (ground.lane_width_m > 0.0 && std::abs(x) <= half_road) {
    // Lane boundaries at lateral (k + 1/2) lane_width: the camera drives in the middle of one.
    const double boundary = (std::round(x / ground.lane_width_m - 0.5) + 0.5) * ground.lane_width_m;
    const double period = ground.dash_m + ground.gap_m;
    const double along = z - period * std::floor(z / period);
    if (std::abs(x - boundary) < 0.5 * ground.marking_width_m &&
        std::abs(boundary) < half_road - ground.marking_width_m && along < ground.dash_m) {
      shade.colour = ground.marking_colour;
    }
  }
  // A texture cell spans f cell h / t^2 rows at depth t: the texture fades out where that
  // falls below two rows, instead of aliasing into noise near the horizon.
  const double cell_rows = camera.f * ground.texture_cell_m * camera.height / (t * t);
  const double fade = std::clamp(0.5 * cell_rows, 0.0, 1.0);
  shade.texture = ground.texture * fade *
                  Texture(key, x / ground.texture_cell_m, z / ground.texture_cell_m);
  return shade;
}

Shade SkyShade(const StreetSky& sky, std::uint64_t key, const cv::Vec3d& d) {
  const double elevation = std::atan2(-d[1], std::hypot(d[0], d[2])) / kDegree;
  const double azimuth = std::atan2(d[0], d[2]) / kDegree;
  const double s = std::clamp(elevation / sky.gradient_deg, 0.0, 1.0);
  Shade shade;
  for (int c = 0; c < 3; ++c) {
    shade.colour[c] = (1.0 - s) * sky.horizon_colour[c] + s * sky.zenith_colour[c];
  }
  // Broad, faint clouds: a lattice cell of 4 degrees.
  shade.texture = sky.texture * Texture(key, azimuth / 4.0, elevation / 4.0);
  return shade;
}

Shade BackdropShade(const StreetBackdrop& backdrop, std::uint64_t key, double x, double y) {
  const auto facade = static_cast<std::int64_t>(std::floor(x / backdrop.facade_width_m));
  Shade shade;
  const std::uint64_t facade_key = Mix(key ^ 0x5bd1e995ULL, static_cast<std::uint64_t>(facade));
  for (int c = 0; c < 3; ++c) {
    const double u = UnitInterval(Mix(facade_key, static_cast<std::uint64_t>(c)));
    shade.colour[c] = std::clamp(backdrop.colour[c] + backdrop.colour_spread * (2.0 * u - 1.0),
                                 0.0, 255.0);
  }
  const double up = -y;
  const double across = x - facade * backdrop.facade_width_m;
  const double height = FacadeHeight(backdrop, key, facade);
  const double cell_x = across / kWindowPeriodX - std::floor(across / kWindowPeriodX);
  const double cell_y = (up - kGroundFloorM) / kWindowPeriodY;
  const bool window = backdrop.window_contrast > 0.0 && up > kGroundFloorM &&
                      up < height - 1.0 && std::abs(cell_x - 0.5) < 0.5 * kWindowShare &&
                      std::abs(cell_y - std::floor(cell_y) - 0.5) < 0.5 * kWindowShare;
  shade.texture = backdrop.texture * Texture(key, x / backdrop.texture_cell_m,
                                             up / backdrop.texture_cell_m);
  if (window) shade.texture -= backdrop.window_contrast;
  return shade;
}

Shade ObjectShade(const Billboard& b, double x, double y) {
  const SceneObject& o = *b.object;
  Shade shade;
  shade.colour = o.colour;
  if (o.texture > 0.0) {
    shade.texture =
        o.texture * Texture(b.key, (x - b.lateral) / o.texture_cell_m, y / o.texture_cell_m);
  }
  return shade;
}

// The projected area of a billboard in the left image, pixels: its outline's share of the
// projected quadrilateral (1 rectangle, pi/4 ellipse, 1/2 triangle), from the shoelace formula.
double ProjectedArea(const Camera& camera, const Billboard& b) {
  const double x0 = b.lateral - b.half_width, x1 = b.lateral + b.half_width;
  const cv::Point2d corners[4] = {camera.Project(x0, 0, b.distance),
                                  camera.Project(x1, 0, b.distance),
                                  camera.Project(x1, -b.height, b.distance),
                                  camera.Project(x0, -b.height, b.distance)};
  double twice = 0.0;
  for (int i = 0; i < 4; ++i) twice += corners[i].cross(corners[(i + 1) % 4]);
  const double quad = 0.5 * std::abs(twice);
  switch (b.object->shape) {
    case SynthShape::kEllipse:
      return quad * std::numbers::pi / 4.0;
    case SynthShape::kTriangle:
      return quad / 2.0;
    default:
      return quad;
  }
}


// The objects present at `frame` that the camera has not passed, in scene order.
std::vector<Billboard> PresentBillboards(const Scene& scene, const Camera& camera, int frame,
                                         const std::vector<std::uint64_t>& keys) {
  std::vector<Billboard> billboards;
  for (size_t i = 0; i < scene.objects.size(); ++i) {
    const SceneObject& o = scene.objects[i];
    if (frame < o.entry || (o.exit >= 0 && frame > o.exit)) continue;
    const GroundKeyframe pose = InterpolateGroundPath(o.ground_path, frame);
    Billboard b;
    b.object = &o;
    b.key = keys[i];
    b.lateral = pose.lateral;
    b.distance = pose.distance;
    b.half_width = 0.5 * o.width_m;
    b.height = o.height_m;
    b.centre_depth = camera.DepthOf(-0.5 * b.height, b.distance);
    if (b.centre_depth < kPassedDepthM) continue;
    billboards.push_back(b);
  }
  return billboards;
}

// What one view needs besides its camera.
struct ViewSetup {
  double baseline_offset = 0.0;  // the view's X: 0 left, baseline_m right
  double gain = 1.0, sigma = 0.0;
  std::uint64_t noise_seed = 0;
};

// Ray casts and shades one view. Fills `ids`, and for the left view (non-null pointers) the
// disparity, the classes and `owner` (each pixel's billboard index, -1 for none).
void RenderView(const Scene& scene, const Camera& camera, const std::vector<Billboard>& billboards,
                const std::array<std::uint64_t, 3>& keys, const ViewSetup& view, cv::Mat* image,
                cv::Mat* ids, cv::Mat* disparity, cv::Mat* classes, std::vector<int>* owner) {
  const StreetSetting& street = *scene.street;
  const double focal_baseline = scene.focal_px * scene.baseline_m;
  GaussianSource noise(view.noise_seed);
  for (int y = 0; y < image->rows; ++y) {
    cv::Vec3b* pixels = image->ptr<cv::Vec3b>(y);
    int* id_row = ids->ptr<int>(y);
    for (int x = 0; x < image->cols; ++x) {
      const cv::Vec3d d = camera.Ray(x, y);
      const RayHit hit = Cast(camera, street, keys[2], billboards, view.baseline_offset, d);
      const double wx = view.baseline_offset + hit.t * d[0];
      const double wy = -camera.height + hit.t * d[1];
      const double wz = camera.distance + hit.t * d[2];
      Shade shade;
      switch (hit.what) {
        case PixelClass::kGround:
          shade = GroundShade(street.ground, keys[0], camera, wx, wz, hit.t);
          break;
        case PixelClass::kOther:
          shade = BackdropShade(street.backdrop, keys[2], wx, wy);
          break;
        case PixelClass::kObject:
          shade = ObjectShade(billboards[hit.billboard], wx, wy);
          break;
        default:
          shade = SkyShade(street.sky, keys[1], d);
      }
      // Output is BGR; colours are RGB. Noise is drawn in B, G, R order for every pixel.
      for (int c = 0; c < 3; ++c) {
        double value = view.gain * (shade.colour[2 - c] + shade.texture);
        if (view.sigma > 0.0) value += view.sigma * noise.Next();
        pixels[x][c] = ToByte(value);
      }
      id_row[x] = hit.billboard >= 0 ? billboards[hit.billboard].object->id : 0;
      if (disparity == nullptr) continue;
      const bool sky = hit.what == PixelClass::kSky;
      disparity->at<float>(y, x) = sky ? 0.f : static_cast<float>(focal_baseline / hit.t);
      classes->at<std::uint8_t>(y, x) = static_cast<std::uint8_t>(hit.what);
      (*owner)[static_cast<size_t>(y) * image->cols + x] = hit.billboard;
    }
  }
}

// Each billboard's visible box in the left view and the share of its projected area visible.
std::vector<GtObject> StreetGroundTruth(const Scene& scene, const Camera& camera, int frame,
                                        const std::vector<Billboard>& billboards,
                                        const std::vector<int>& owner) {
  struct Visible {
    long long pixels = 0;
    int x0 = 0, y0 = 0, x1 = -1, y1 = -1;
  };
  std::vector<Visible> visible(billboards.size());
  for (int y = 0; y < scene.height; ++y) {
    for (int x = 0; x < scene.width; ++x) {
      const int k = owner[static_cast<size_t>(y) * scene.width + x];
      if (k < 0) continue;
      Visible& v = visible[k];
      if (v.pixels == 0) {
        v.x0 = v.x1 = x;
        v.y0 = y;
      }
      ++v.pixels;
      v.x0 = std::min(v.x0, x);
      v.x1 = std::max(v.x1, x);
      v.y1 = y;
    }
  }
  std::vector<GtObject> objects;
  for (size_t k = 0; k < billboards.size(); ++k) {
    const Billboard& b = billboards[k];
    GtObject gt;
    gt.frame = frame;
    gt.id = b.object->id;
    gt.kind = b.object->kind;
    gt.disparity = scene.focal_px * scene.baseline_m / b.centre_depth;
    const Visible& v = visible[k];
    if (v.pixels > 0) {
      gt.box = cv::Rect2d(v.x0, v.y0, v.x1 - v.x0 + 1, v.y1 - v.y0 + 1);
      gt.visible_fraction =
          std::min(1.0, static_cast<double>(v.pixels) / ProjectedArea(camera, b));
    }
    objects.push_back(gt);
  }
  std::sort(objects.begin(), objects.end(),
            [](const GtObject& a, const GtObject& b) { return a.id < b.id; });
  return objects;
}

}  // namespace

std::array<double, 3> StreetHorizon(const Scene& scene) {
  const double cy = 0.5 * (scene.height - 1);
  return {0.0, 1.0, -(cy - scene.focal_px * std::tan(scene.pitch_deg * kDegree))};
}

double CameraDistance(const Scene& scene, int frame) {
  return scene.speed_mps * frame / scene.fps;
}

StreetRenderer::StreetRenderer(Scene scene) : scene_(std::move(scene)) {
  ATTEND_CHECK(scene_.street.has_value()) << "a street renderer needs a street scene";
  const std::uint64_t surface = Mix(scene_.seed, synth_sampling::kSurfaceDomain);
  ground_key_ = Mix(surface, kGroundDomain);
  sky_key_ = Mix(surface, kSkyDomain);
  backdrop_key_ = Mix(surface, kBackdropDomain);
  for (const SceneObject& object : scene_.objects) {
    // Keyed by id, as in the other scenes, so adding an object leaves the others unchanged.
    std::mt19937_64 engine(Mix(surface, static_cast<std::uint64_t>(object.id)));
    texture_keys_.push_back(engine());
  }
}

RenderedFrame StreetRenderer::Render(int frame) const {
  ATTEND_CHECK(frame >= 0) << "frame " << frame;
  const int width = scene_.width;
  const int height = scene_.height;
  const Camera camera = MakeCamera(scene_, frame);
  const std::vector<Billboard> billboards =
      PresentBillboards(scene_, camera, frame, texture_keys_);

  RenderedFrame out;
  out.frame = frame;
  out.left.create(height, width, CV_8UC3);
  out.right.create(height, width, CV_8UC3);
  out.disparity.create(height, width, CV_32FC1);
  out.left_ids.create(height, width, CV_32SC1);
  out.right_ids.create(height, width, CV_32SC1);
  out.classes.create(height, width, CV_8UC1);

  const std::uint64_t frame_seed =
      Mix(Mix(scene_.seed, synth_sampling::kNoiseDomain), static_cast<std::uint64_t>(frame));
  const std::array<std::uint64_t, 3> keys = {ground_key_, sky_key_, backdrop_key_};
  ViewSetup view;
  view.gain = InterpolateGain(scene_.brightness, frame);
  view.sigma = scene_.noise_left;
  view.noise_seed = Mix(frame_seed, 0);
  std::vector<int> owner(static_cast<size_t>(width) * height, -1);
  RenderView(scene_, camera, billboards, keys, view, &out.left, &out.left_ids, &out.disparity,
             &out.classes, &owner);
  view.baseline_offset = scene_.baseline_m;
  view.sigma = scene_.noise_right;
  view.noise_seed = Mix(frame_seed, 1);
  RenderView(scene_, camera, billboards, keys, view, &out.right, &out.right_ids, nullptr, nullptr,
             nullptr);
  out.objects = StreetGroundTruth(scene_, camera, frame, billboards, owner);
  return out;
}

}  // namespace attend
