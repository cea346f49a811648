#include "synth/render_sequence.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <charconv>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <opencv2/imgcodecs.hpp>
#include <system_error>
#include <thread>
#include <vector>

#include "io/ground_truth.h"
#include "io/image_file.h"
#include "io/pfm.h"
#include "io/stereo_calibration.h"
#include "synth/renderer.h"
#include "synth/street_renderer.h"
#include "util/error.h"
#include "util/output_folder.h"

namespace attend {

namespace fs = std::filesystem;

namespace {

// The shortest text that reads back as the same double.
std::string ShortestNumber(double value) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof(buffer), value);
  return std::string(buffer, result.ptr);
}

// A YAML double-quoted scalar, so that any scene name reads back unchanged.
std::string QuotedYaml(const std::string& text) {
  std::string quoted = "\"";
  for (const char c : text) {
    if (c == '"' || c == '\\') {
      quoted += '\\';
      quoted += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char escape[8];
      std::snprintf(escape, sizeof(escape), "\\x%02x", static_cast<unsigned char>(c));
      quoted += escape;
    } else {
      quoted += c;
    }
  }
  return quoted + "\"";
}

// Makes `folder` ready for the layout. Only a folder that holds an earlier `attend synth`
// output (its sequence.yaml says so) may be overwritten, and then only the layout's own
// entries are removed, so stale frames of a longer earlier render cannot survive next to the
// new ones and a recorded sequence is never deleted.
FolderLock PrepareFolder(const fs::path& folder, bool overwrite, bool street) {
  OutputFolderRules rules;
  rules.what = "sequence";
  rules.own_entries = {"left",          "right",           "gt/disparity", "gt/classes",
                       "gt/horizon.txt", "gt/objects.csv", "sequence.yaml", "calib.yaml"};
  rules.is_previous_output = [](const std::string& existing) {
    std::ifstream in(fs::path(existing) / "sequence.yaml");
    std::string line;
    while (std::getline(in, line)) {
      if (line.rfind("generator: attend synth", 0) == 0) return true;
    }
    return false;
  };
  FolderLock lock = PrepareOutputFolder(folder.string(), overwrite, rules);
  std::error_code error;
  std::vector<fs::path> subfolders = {folder / "left", folder / "right", folder / "gt" / "disparity"};
  if (street) subfolders.push_back(folder / "gt" / "classes");
  for (const fs::path& sub : subfolders) {
    fs::create_directories(sub, error);
    if (error) throw OutputError(sub.string() + ": cannot create the folder: " + error.message());
  }
  return lock;
}

void WritePng(const fs::path& path, const cv::Mat& image) {
  // Fixed compression so that the bytes do not depend on OpenCV's default. The sensor noise
  // leaves little to compress: level 1 is 5 % larger than level 3 and much faster.
  const std::vector<int> params = {cv::IMWRITE_PNG_COMPRESSION, 1};
  bool written = false;
  try {
    written = WriteImage(path.string(), image, params);
  } catch (const cv::Exception& e) {
    throw OutputError(path.string() + ": cannot write the image: " + e.what());
  }
  if (!written) throw OutputError(path.string() + ": cannot write the image");
}

void WriteSequenceYaml(const fs::path& path, const Scene& scene) {
  std::ofstream out(path);
  if (!out) throw OutputError(path.string() + ": cannot write the sequence description");
  // The scene's file name only, so that the same scene read from another folder gives the
  // same bytes.
  const std::string scene_file =
      scene.source.empty() ? "a scene" : fs::path(scene.source).filename().string();
  out << "# Rendered by attend synth from " << scene_file << ", seed " << scene.seed << ".\n"
      << "name: " << QuotedYaml(scene.name) << "\n"
      << "fps: " << ShortestNumber(scene.fps) << "\n"
      << "focal_px: " << ShortestNumber(scene.focal_px) << "\n"
      << "baseline_m: " << ShortestNumber(scene.baseline_m) << "\n"
      << "generator: attend synth\n"
      << "frames: " << scene.frames << "\n";
  if (!out) throw OutputError(path.string() + ": error while writing the sequence description");
}

// SEQ/calib.yaml in the rectified form (docs/STEREO3D.md). The renderer places an object by
// its left-view pixel (x, y), pixel centres at whole coordinates, and its depth Z, and draws it
// in the right view at x - f B / Z on the same row: the rectified pair of P1, P2 below. Its
// objects have no X, Y of their own; the principal point is the image centre ((width - 1) / 2,
// (height - 1) / 2), so an object drawn there is on the optical axis and X = (x - cx) Z / f.
void WriteCalibrationYaml(const fs::path& path, const Scene& scene) {
  StereoCalibration calibration =
      NominalCalibration(scene.focal_px, scene.baseline_m, {scene.width, scene.height}, "");
  calibration.form = StereoCalibration::Form::kRectified;
  WriteStereoCalibration(calibration, path.string());
}

// SEQ/gt/horizon.txt of a street scene: the horizon a u + b v + c = 0 in left-image pixels.
void WriteHorizon(const fs::path& path, const Scene& scene) {
  const std::array<double, 3> line = StreetHorizon(scene);
  std::ofstream out(path);
  if (!out) throw OutputError(path.string() + ": cannot write the horizon");
  out << "# The horizon of the left view, a u + b v + c = 0 in pixels (docs/SYNTH.md): a b c\n"
      << ShortestNumber(line[0]) << " " << ShortestNumber(line[1]) << " "
      << ShortestNumber(line[2]) << "\n";
  if (!out) throw OutputError(path.string() + ": error while writing the horizon");
}

}  // namespace

std::string SynthOptions::Check() const {
  if (frames.has_value() && *frames < 1) return "frames must be >= 1";
  if (threads < 0) return "threads must be >= 0";
  return "";
}

std::string SynthSummary::BriefReport() const {
  return "wrote " + std::to_string(frames) + " frames of " + std::to_string(objects) +
         " objects (seed " + std::to_string(seed) + ") to " + path;
}

SynthSummary RenderSequence(const Scene& scene, const std::string& out_folder,
                            const SynthOptions& options) {
  const std::string options_error = options.Check();
  if (!options_error.empty()) throw ConfigError("synth options: " + options_error);
  Scene effective = scene;
  if (options.seed.has_value()) effective.seed = *options.seed;
  if (options.frames.has_value()) effective.frames = *options.frames;
  const SceneRenderer renderer(std::move(effective));  // validates before anything is written
  const Scene& used = renderer.scene();

  const fs::path folder(out_folder);
  const FolderLock lock = PrepareFolder(folder, options.overwrite, used.street.has_value());

  // Frames are independent, so workers take them in turn; the ground truth is gathered per
  // frame and written in frame order.
  std::vector<std::vector<GtObject>> objects_of_frame(used.frames);
  std::atomic<int> next_frame = 0;
  std::exception_ptr failure;
  std::mutex failure_mutex;
  auto work = [&] {
    for (int frame = next_frame++; frame < used.frames; frame = next_frame++) {
      try {
        RenderedFrame rendered = renderer.Render(frame);
        const std::string stem = FrameStem(frame);
        WritePng(folder / "left" / (stem + ".png"), rendered.left);
        WritePng(folder / "right" / (stem + ".png"), rendered.right);
        WritePfm(GtDisparityPath(out_folder, frame), rendered.disparity);
        if (!rendered.classes.empty()) {
          WritePng(folder / "gt" / "classes" / (stem + ".png"), rendered.classes);
        }
        objects_of_frame[frame] = std::move(rendered.objects);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(failure_mutex);
        if (!failure) failure = std::current_exception();
        next_frame = used.frames;  // the others stop after their current frame
      }
    }
  };
  const int hardware = static_cast<int>(std::thread::hardware_concurrency());
  const int threads =
      std::clamp(options.threads > 0 ? options.threads : std::max(hardware, 1), 1, used.frames);
  std::vector<std::thread> workers;
  for (int i = 1; i < threads; ++i) {
    try {
      workers.emplace_back(work);
    } catch (const std::system_error&) {
      break;  // no more threads to be had: the ones running take all frames
    }
  }
  work();
  for (std::thread& worker : workers) worker.join();
  if (failure) std::rethrow_exception(failure);

  std::vector<GtObject> ground_truth;
  for (const std::vector<GtObject>& objects : objects_of_frame) {
    ground_truth.insert(ground_truth.end(), objects.begin(), objects.end());
  }
  WriteObjectsCsv((folder / "gt" / "objects.csv").string(), ground_truth);
  if (used.street.has_value()) WriteHorizon(folder / "gt" / "horizon.txt", used);
  WriteCalibrationYaml(folder / "calib.yaml", used);
  // Last, so that a folder with a sequence.yaml is a complete render.
  WriteSequenceYaml(folder / "sequence.yaml", used);

  SynthSummary summary;
  summary.frames = used.frames;
  summary.objects = static_cast<int>(used.objects.size());
  summary.seed = used.seed;
  summary.path = out_folder;
  return summary;
}

}  // namespace attend
