#include "synth/render_sequence.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "io/ground_truth.h"
#include "io/pfm.h"
#include "io/stereo_calibration.h"
#include "synth/renderer.h"
#include "tests/support/temp_dir.h"
#include "util/error.h"

namespace attend {
namespace {

namespace fs = std::filesystem;

// Small and short so that the whole layout is written quickly; f * B = 10.
const char* const kSceneText = R"(name: tiny
width: 48
height: 36
frames: 4
fps: 10
seed: 5
camera: {focal_px: 80, baseline_m: 0.125}
noise: {left: 2, right: 2}
background: {depth: 5, colour: [110, 115, 120], texture: 15, texture_cell: 0.2}
brightness: [{frame: 0, gain: 1}, {frame: 3, gain: 0.7}]
objects:
  - id: 1
    shape: rectangle
    size: [0.3, 0.2]
    colour: [220, 30, 30]
    texture: 10
    path: [{frame: 0, x: 10, y: 18, depth: 2}, {frame: 3, x: 30, y: 18, depth: 2}]
  - id: 2
    kind: skin
    shape: ellipse
    size: [0.15, 0.2]
    colour: [225, 170, 140]
    path: [{frame: 0, x: 24, y: 16, depth: 1.25}]
    entry: 1
  - id: 3
    shape: blob
    size: [0.1, 0.1]
    colour: [30, 200, 40]
    path: [{frame: 0, x: 24, y: 16, depth: 3}]
    exit: 2
)";

std::string ReadBytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// Every regular file below `folder`, relative, sorted.
std::vector<std::string> FilesBelow(const fs::path& folder) {
  std::vector<std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(folder)) {
    if (entry.is_regular_file()) files.push_back(fs::relative(entry.path(), folder).string());
  }
  std::sort(files.begin(), files.end());
  return files;
}

TEST(SynthRenderSequence, WritesTheLayoutByteIdenticallyForTheSameSeed) {
  testing::TempDir dir;
  const Scene scene = ParseScene(kSceneText, "tiny.yaml");
  SynthOptions one_thread;
  one_thread.threads = 1;
  const SynthSummary summary = RenderSequence(scene, dir.File("a"), one_thread);
  EXPECT_EQ(summary.frames, 4);
  EXPECT_EQ(summary.objects, 3);
  EXPECT_EQ(summary.seed, 5u);
  EXPECT_EQ(summary.path, dir.File("a"));
  EXPECT_NE(summary.BriefReport().find("wrote 4 frames of 3 objects"), std::string::npos);
  SynthOptions three_threads;
  three_threads.threads = 3;
  RenderSequence(scene, dir.File("b"), three_threads);
  const std::vector<std::string> files = FilesBelow(dir.File("a"));
  const std::vector<std::string> expected = {"calib.yaml",
                                             "gt/disparity/000000.pfm", "gt/disparity/000001.pfm",
                                             "gt/disparity/000002.pfm", "gt/disparity/000003.pfm",
                                             "gt/objects.csv",          "left/000000.png",
                                             "left/000001.png",         "left/000002.png",
                                             "left/000003.png",         "right/000000.png",
                                             "right/000001.png",        "right/000002.png",
                                             "right/000003.png",        "sequence.yaml"};
  EXPECT_EQ(files, expected);
  EXPECT_EQ(FilesBelow(dir.File("b")), expected);
  for (const std::string& file : files) {
    EXPECT_EQ(ReadBytes(dir.path() / "a" / file), ReadBytes(dir.path() / "b" / file)) << file;
  }

  SynthOptions other_seed;
  other_seed.seed = 6;
  EXPECT_EQ(RenderSequence(scene, dir.File("c"), other_seed).seed, 6u);
  EXPECT_NE(ReadBytes(dir.path() / "a" / "left/000001.png"),
            ReadBytes(dir.path() / "c" / "left/000001.png"));
  EXPECT_EQ(ReadBytes(dir.path() / "a" / "gt/objects.csv"),
            ReadBytes(dir.path() / "c" / "gt/objects.csv"));

  const std::string yaml = ReadBytes(dir.path() / "a" / "sequence.yaml");
  for (const char* line : {"name: \"tiny\"\n", "fps: 10\n", "focal_px: 80\n", "baseline_m: 0.125\n",
                           "generator: attend synth\n", "frames: 4\n"}) {
    EXPECT_NE(yaml.find(line), std::string::npos) << line << " in\n" << yaml;
  }
  // SEQ/calib.yaml: the rectified pair of the scene's focal length and baseline, the principal
  // point at the image centre (docs/STEREO3D.md).
  const StereoCalibration calibration = ReadStereoCalibration(dir.File("a/calib.yaml"));
  EXPECT_EQ(calibration.form, StereoCalibration::Form::kRectified);
  EXPECT_EQ(calibration.image_size, cv::Size(48, 36));
  EXPECT_DOUBLE_EQ(calibration.focal_px(), 80.0);
  EXPECT_DOUBLE_EQ(calibration.baseline_m(), 0.125);
  EXPECT_DOUBLE_EQ(calibration.cx(), 23.5);
  EXPECT_DOUBLE_EQ(calibration.cy(), 17.5);
  // The images are what the renderer makes.
  const RenderedFrame frame2 = SceneRenderer(scene).Render(2);
  const cv::Mat left = cv::imread(dir.File("a/left/000002.png"), cv::IMREAD_UNCHANGED);
  const cv::Mat right = cv::imread(dir.File("a/right/000002.png"), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(left.type(), CV_8UC3);
  EXPECT_EQ(cv::norm(left, frame2.left, cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(right, frame2.right, cv::NORM_INF), 0.0);
}

TEST(SynthRenderSequence, WrittenDisparityIsFocalTimesBaselineOverDepth) {
  testing::TempDir dir;
  const Scene scene = ParseScene(kSceneText, "tiny.yaml");
  RenderSequence(scene, dir.File("seq"), {});
  const SceneRenderer renderer(scene);
  const std::map<int, double> depth_of = {{0, 5.0}, {1, 2.0}, {2, 1.25}, {3, 3.0}};
  for (int frame = 0; frame < scene.frames; ++frame) {
    const cv::Mat disparity = ReadPfm(GtDisparityPath(dir.File("seq"), frame));
    const cv::Mat ids = renderer.Render(frame).left_ids;
    ASSERT_EQ(disparity.size(), cv::Size(48, 36));
    for (int y = 0; y < disparity.rows; ++y) {
      for (int x = 0; x < disparity.cols; ++x) {
        ASSERT_FLOAT_EQ(disparity.at<float>(y, x),
                        static_cast<float>(10.0 / depth_of.at(ids.at<int>(y, x))))
            << "frame " << frame << " at " << x << "," << y;
      }
    }
  }
}

TEST(SynthRenderSequence, ObjectsCsvHasARowPerPresentObjectWithTheIdMapBox) {
  testing::TempDir dir;
  const Scene scene = ParseScene(kSceneText, "tiny.yaml");
  RenderSequence(scene, dir.File("seq"), {});
  const std::vector<GtObject> rows = ReadObjectsCsv(dir.File("seq/gt/objects.csv"));
  // Object 1: frames 0-3, object 2: 1-3, object 3: 0-2.
  ASSERT_EQ(rows.size(), 4u + 3u + 3u);
  const SceneRenderer renderer(scene);
  std::map<int, int> rows_of;
  bool saw_hidden = false;
  for (const GtObject& row : rows) {
    ++rows_of[row.id];
    const cv::Mat ids = renderer.Render(row.frame).left_ids;
    const cv::Rect box = cv::boundingRect(ids == row.id);
    EXPECT_EQ(row.box, cv::Rect2d(box)) << "frame " << row.frame << " id " << row.id;
    EXPECT_EQ(row.visible_fraction == 0.0, box.area() == 0);
    EXPECT_EQ(row.kind, row.id == 2 ? "skin" : "object");
    saw_hidden |= row.visible_fraction == 0.0;
  }
  EXPECT_EQ(rows_of, (std::map<int, int>{{1, 4}, {2, 3}, {3, 3}}));
  // Object 3 (small, behind the face from frame 1) is fully hidden.
  EXPECT_TRUE(saw_hidden);
}

TEST(SynthRenderSequence, RefusesANonEmptyFolderAndOverwritesOnlyItsOwnFiles) {
  testing::TempDir dir;
  const Scene scene = ParseScene(kSceneText, "tiny.yaml");
  const std::string folder = dir.File("seq");
  SynthOptions options;
  options.frames = 4;
  RenderSequence(scene, folder, options);
  dir.Write("seq/notes.txt", "keep me");
  try {
    RenderSequence(scene, folder, {});
    FAIL() << "a non-empty folder was accepted";
  } catch (const OutputError& e) {
    EXPECT_NE(std::string(e.what()).find(folder + ": the output folder is not empty"),
              std::string::npos)
        << e.what();
  }

  // Over an earlier render, --overwrite replaces the layout and keeps other files.
  options.overwrite = true;
  options.frames = 2;
  EXPECT_EQ(RenderSequence(scene, folder, options).frames, 2);
  EXPECT_EQ(ReadBytes(dir.path() / "seq" / "notes.txt"), "keep me");
  EXPECT_TRUE(fs::exists(dir.path() / "seq" / "right" / "000001.png"));
  EXPECT_FALSE(fs::exists(dir.path() / "seq" / "left" / "000003.png"));
  EXPECT_FALSE(fs::exists(dir.path() / "seq" / "right" / "000002.png"));

  const std::string file = dir.Write("file", "x");
  EXPECT_THROW(RenderSequence(scene, file, options), OutputError);
  options.frames = 0;
  EXPECT_THROW(RenderSequence(scene, dir.File("new"), options), ConfigError);
  EXPECT_FALSE(fs::exists(dir.path() / "new"));
}

TEST(SynthRenderSequence, OverwriteNeverTouchesARecordedSequence) {
  // A folder in the same layout that attend synth did not write (a real recording) is refused
  // even with overwrite, and keeps its frames.
  testing::TempDir dir;
  dir.Write("real/left/capture_0001.png", "frame");
  dir.Write("real/right/capture_0001.png", "frame");
  SynthOptions options;
  options.overwrite = true;
  EXPECT_THROW(RenderSequence(ParseScene(kSceneText, "tiny.yaml"), dir.File("real"), options),
               OutputError);
  EXPECT_TRUE(fs::exists(dir.path() / "real" / "left" / "capture_0001.png"));
}

TEST(SynthOptions, DefaultsAreValid) {
  EXPECT_EQ(SynthOptions().Check(), "");
  SynthOptions options;
  options.frames = 0;
  EXPECT_NE(options.Check().find("frames"), std::string::npos);
  options.frames = 1;
  options.threads = -1;
  EXPECT_NE(options.Check().find("threads"), std::string::npos);
}

}  // namespace
}  // namespace attend
