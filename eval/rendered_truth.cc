#include "eval/rendered_truth.h"

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <sstream>
#include <vector>

#include "io/folder_source.h"
#include "io/frame_source.h"
#include "io/ground_truth.h"
#include "io/image_file.h"
#include "io/pfm.h"
#include "util/error.h"

namespace attend {

namespace {

namespace fs = std::filesystem;

// The classes of gt/classes (docs/SYNTH.md): 0 unknown, 1 object, 2 ground, 3 sky, 4 other.
constexpr std::uint8_t kGroundClass = 2;
constexpr std::uint8_t kLastClass = 4;

// The frame index of a map named NNNNNN.png, or -1 for another name.
int FrameOfFile(const fs::path& path) {
  if (path.extension() != ".png") return -1;
  const std::string stem = path.stem().string();
  if (stem.empty() || stem.size() > 9 ||
      stem.find_first_not_of("0123456789") != std::string::npos) {
    return -1;
  }
  return std::stoi(stem);
}

HorizonLine ReadHorizon(const fs::path& path) {
  HorizonLine horizon;
  std::error_code error;
  if (!fs::exists(path, error)) return horizon;
  std::ifstream in(path);
  if (!in) throw InputError(path.string() + ": cannot read the horizon");
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    std::string rest;
    if (!(fields >> horizon.a >> horizon.b >> horizon.c) || (fields >> rest) || horizon.b == 0.0) {
      throw InputError(path.string() + ":" + std::to_string(number) +
                       ": expected 'a b c' of the horizon a u + b v + c = 0 with b != 0, got '" +
                       line + "'");
    }
    return horizon;
  }
  throw InputError(path.string() + ": no horizon line 'a b c'");
}

// The focal length times the baseline of SEQ/sequence.yaml, pixels times metres.
double FocalBaseline(const fs::path& folder) {
  const fs::path yaml = folder / "sequence.yaml";
  std::error_code error;
  if (!fs::exists(yaml, error)) {
    throw InputError(yaml.string() + ": missing; rendered truth needs its focal_px and baseline_m");
  }
  SequenceInfo info;
  ReadSequenceYaml(yaml.string(), &info);
  if (info.focal_px <= 0.0 || info.baseline_m <= 0.0) {
    throw InputError(yaml.string() + ": focal_px and baseline_m must be > 0 to turn the "
                     "disparities of gt/disparity into depths");
  }
  return info.focal_px * info.baseline_m;
}

// The truth points of one frame from its class and disparity maps.
std::vector<TruthPoint> FramePoints(const cv::Mat& classes, const cv::Mat& disparity,
                                    double focal_baseline, const std::string& classes_path) {
  std::vector<TruthPoint> points;
  for (int v = 0; v < classes.rows; ++v) {
    const std::uint8_t* class_row = classes.ptr<std::uint8_t>(v);
    for (int u = 0; u < classes.cols; ++u) {
      if (class_row[u] > kLastClass) {
        throw InputError(classes_path + ": pixel (" + std::to_string(u) + ", " +
                         std::to_string(v) + ") has class " + std::to_string(class_row[u]) +
                         ", not one of 0..4");
      }
    }
    if (v % kRenderedPointStep != 0) continue;
    const float* d_row = disparity.ptr<float>(v);
    for (int u = 0; u < classes.cols; u += kRenderedPointStep) {
      // Not > 0: unknown (0, the sky), or not a number: no point.
      if (!(d_row[u] > 0.f) || !std::isfinite(d_row[u])) continue;
      TruthPoint point;
      point.u = static_cast<float>(u);
      point.v = static_cast<float>(v);
      point.depth_m = static_cast<float>(focal_baseline / d_row[u]);
      point.ground = class_row[u] == kGroundClass;
      points.push_back(point);
    }
  }
  return points;
}

}  // namespace

bool HasRenderedTruth(const std::string& gt_folder) {
  std::error_code error;
  return fs::is_directory(fs::path(gt_folder) / "classes", error);
}

SceneTruth ReadRenderedTruth(const std::string& sequence_folder) {
  const fs::path folder(sequence_folder);
  const fs::path gt = folder / "gt";
  const fs::path classes_folder = gt / "classes";
  std::error_code error;
  if (!fs::is_directory(classes_folder, error)) {
    throw InputError(classes_folder.string() + ": no class maps (not a rendered street scene)");
  }
  const double focal_baseline = FocalBaseline(folder);
  const HorizonLine horizon = ReadHorizon(gt / "horizon.txt");

  SceneTruth truth;
  for (const auto& entry : fs::directory_iterator(classes_folder)) {
    const int frame = FrameOfFile(entry.path());
    if (frame < 0) continue;
    const std::string classes_path = entry.path().string();
    const cv::Mat classes = ReadImageFile(classes_path, cv::IMREAD_UNCHANGED, classes_path);
    if (classes.type() != CV_8UC1) {
      throw InputError(classes_path + ": a class map must be one 8-bit channel");
    }
    const std::string disparity_path = GtDisparityPath(sequence_folder, frame);
    if (!fs::exists(disparity_path, error)) {
      throw InputError(disparity_path + ": missing; the class map " + classes_path +
                       " needs its disparity");
    }
    const cv::Mat disparity = ReadPfmOneChannel(disparity_path, "disparity ground truth");
    if (disparity.size() != classes.size()) {
      throw InputError(disparity_path + ": " + std::to_string(disparity.cols) + "x" +
                       std::to_string(disparity.rows) + " does not match its class map (" +
                       std::to_string(classes.cols) + "x" + std::to_string(classes.rows) + ")");
    }
    FrameTruth& frame_truth = truth[frame];
    frame_truth.frame = frame;
    frame_truth.image_size = classes.size();
    frame_truth.horizon = horizon;
    frame_truth.points = FramePoints(classes, disparity, focal_baseline, classes_path);
  }

  const fs::path objects = gt / "objects.csv";
  if (fs::exists(objects, error)) {
    for (const GtObject& row : ReadObjectsCsv(objects.string())) {
      const auto it = truth.find(row.frame);
      if (it == truth.end() || row.box.empty()) continue;
      TruthObject object;
      object.id = row.id;
      object.box = row.box;
      object.kind = row.kind;
      if (row.disparity.has_value() && *row.disparity > 0.0) {
        object.depth_m = focal_baseline / *row.disparity;
      }
      it->second.objects.push_back(object);
    }
  }
  return truth;
}

}  // namespace attend
