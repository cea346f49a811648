// attend run on real-world kinds of input, end to end: a plain folder of frames (--images),
// records in the pixels of the input frames whatever the working size (SPEC 3.3), and grey
// frames. Tests on the reference data in /work/shared/data skip when it is absent.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "io/ground_truth.h"
#include "io/pfm.h"
#include "tests/cli/attend_cli.h"
#include "tests/support/attend_process.h"
#include "tests/support/sequence_maker.h"
#include "tests/support/temp_dir.h"

namespace fs = std::filesystem;

namespace attend {
namespace {

using testing::Attend;
using testing::Contains;
using testing::ReadText;
using testing::Result;


std::vector<nlohmann::json> Frames(const testing::TempDir& dir, const std::string& run) {
  std::vector<nlohmann::json> frames;
  std::istringstream lines(ReadText(dir.File(run + "/frames.jsonl")));
  for (std::string line; std::getline(lines, line);) frames.push_back(nlohmann::json::parse(line));
  return frames;
}

cv::Rect Box(const nlohmann::json& target) {
  const std::vector<int> b = target.at("bbox").get<std::vector<int>>();
  return {b[0], b[1], b[2], b[3]};
}

double Iou(const cv::Rect2d& a, const cv::Rect2d& b) {
  const double inter = (a & b).area();
  const double uni = a.area() + b.area() - inter;
  return uni > 0 ? inter / uni : 0.0;
}

// The best IoU of a new or tracked target of `frame` with `box`.
double BestIou(const nlohmann::json& frame, const cv::Rect2d& box) {
  double best = 0.0;
  for (const nlohmann::json& target : frame.at("targets")) {
    const std::string state = target.at("state");
    if (state != "new" && state != "tracked") continue;
    best = std::max(best, Iou(cv::Rect2d(Box(target)), box));
  }
  return best;
}

// Three static objects of distinct colours on a plain wall, at `width` x `height` with the
// focal length scaled with the width, so the scene looks the same at any size.
std::string ThreeObjectScene(int width, int height, int frames) {
  const double s = width / 320.0;
  std::ostringstream scene;
  scene << "name: three\nwidth: " << width << "\nheight: " << height << "\nframes: " << frames
        << "\nseed: 3\ncamera: {focal_px: " << 300 * s << ", baseline_m: 0.12}\n"
        << "noise: {left: 1, right: 1}\n"
        << "background: {depth: 6.0, colour: [128, 128, 128], texture: 4}\n"
        << "objects:\n"
        << "  - {id: 1, shape: rectangle, size: [0.5, 0.4], colour: [210, 40, 35], path: "
           "[{frame: 0, x: "
        << 80 * s << ", y: " << 70 * s << ", depth: 3.0}]}\n"
        << "  - {id: 2, shape: ellipse, size: [0.5, 0.5], colour: [40, 70, 210], path: "
           "[{frame: 0, x: "
        << 235 * s << ", y: " << 80 * s << ", depth: 3.0}]}\n"
        << "  - {id: 3, shape: rectangle, size: [0.6, 0.4], colour: [40, 190, 60], path: "
           "[{frame: 0, x: "
        << 160 * s << ", y: " << 180 * s << ", depth: 3.0}]}\n";
  return scene.str();
}

TEST(InputCli, RecordsAreInInputPixelsAndEvalScoresThem) {
  testing::TempDir dir;
  dir.Write("three.yaml", ThreeObjectScene(640, 480, 6));
  Result r = Attend(dir, {"synth", "three.yaml", "--out", "seq"});
  ASSERT_EQ(r.status, 0) << r.err;
  // Computed at 320x240 (the default working size), recorded at 640x480.
  r = Attend(dir, {"run", "--sequence", "seq", "--out", "run", "--quiet", "--set",
                   "output.dump=[overlay]"});
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json summary = nlohmann::json::parse(ReadText(dir.File("run/summary.json")));
  EXPECT_EQ(summary["pixels"]["records"], "input");
  EXPECT_EQ(summary["pixels"]["maps"], "working");
  EXPECT_EQ(summary["pixels"]["input_size"], nlohmann::json({640, 480}));
  EXPECT_EQ(summary["pixels"]["working_size"], nlohmann::json({320, 240}));
  EXPECT_EQ(summary["pixels"]["input_from_working"], nlohmann::json({2.0, 2.0}));
  // The overlays stay at the working size.
  EXPECT_EQ(cv::imread(dir.File("run/overlay/000005.png")).size(), cv::Size(320, 240));

  // Every object is under a target in the last frame, in input pixels: the boxes match the
  // 640x480 ground truth closely (at working pixels they would have IoU <= 0.25 at best).
  const std::vector<nlohmann::json> frames = Frames(dir, "run");
  ASSERT_EQ(frames.size(), 6u);
  int checked = 0;
  for (const GtObject& object : ReadObjectsCsv(dir.File("seq/gt/objects.csv"))) {
    if (object.frame != 5) continue;
    SCOPED_TRACE(object.id);
    EXPECT_GE(BestIou(frames[5], object.box), 0.7);
    ++checked;
  }
  EXPECT_EQ(checked, 3);
  for (const nlohmann::json& target : frames[5]["targets"]) {
    const cv::Rect box = Box(target);
    EXPECT_LE(box.x + box.width, 640);
    EXPECT_LE(box.y + box.height, 480);
    // Areas scale by 4: a mask can never exceed its box.
    EXPECT_LE(target["area"].get<int>(), box.area());
    EXPECT_GT(target["area"].get<int>(), box.area() / 4);
  }

  r = Attend(dir, {"eval", "run"});
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json scores = nlohmann::json::parse(r.out);
  EXPECT_EQ(scores["objects"], 3);
  EXPECT_EQ(scores["coverage"], 1.0);
  EXPECT_GE(scores["mean_iou"].get<double>(), 0.7);
}

TEST(InputCli, EvalRefusesARunWrittenInWorkingPixels) {
  testing::TempDir dir;
  testing::MakeFolderSequence(dir.File("seq"), 1, 64, 48, /*stereo=*/true);
  dir.Write("seq/gt/objects.csv", std::string(kObjectsCsvHeader) + "\n0,1,1,2,3,4,1,,object\n");
  // What an older attend wrote: no "pixels", and a working size other than the input's.
  dir.Write("old/frames.jsonl", "{\"frame\":0,\"targets\":[],\"new\":[],\"timings_ms\":{}}\n");
  dir.Write("old/summary.json",
            "{\"frames\":1,\"sequence\":{\"native_size\":[64,48],\"size\":[320,240]}}");
  dir.Write("old/config.yaml", "sequence:\n  folder: " + dir.File("seq") + "\n");
  Result r = Attend(dir, {"eval", "old"});
  EXPECT_EQ(r.status, 3) << r.err;
  EXPECT_TRUE(Contains(r.err, "old/summary.json: this run was written before")) << r.err;
  // The same run at its input size is fine (working and input pixels are the same).
  dir.Write("old/summary.json",
            "{\"frames\":1,\"sequence\":{\"native_size\":[64,48],\"size\":[64,48]}}");
  r = Attend(dir, {"eval", "old"});
  EXPECT_EQ(r.status, 0) << r.err;
}

TEST(InputCli, ImagesRunsOnAPlainFolderOfFrames) {
  testing::TempDir dir;
  // A plain folder of frames as OTB has them (img/0001.jpg ...), here the left views of a
  // rendered stereo scene renamed, plus files that are not frames.
  dir.Write("three.yaml", ThreeObjectScene(320, 240, 4));
  Result r = Attend(dir, {"synth", "three.yaml", "--out", "seq"});
  ASSERT_EQ(r.status, 0) << r.err;
  fs::create_directories(dir.File("img"));
  for (int i = 0; i < 4; ++i) {
    char from[32], to[32];
    std::snprintf(from, sizeof(from), "seq/left/%06d.png", i);
    std::snprintf(to, sizeof(to), "img/%04d.PNG", i + 1);
    fs::copy_file(dir.File(from), dir.File(to));
  }
  dir.Write("img/groundtruth_rect.txt", "1,2,3,4\n");
  // The disparity feature needs stereo: the shipped configuration leaves it out (with a note),
  // an override of the features that keeps it is refused.
  r = Attend(dir, {"run", "--images", "img", "--out", "run", "--set",
                   "features.skin.weight=0.5"});
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_TRUE(Contains(r.err, "features.disparity.enabled=false")) << r.err;
  EXPECT_FALSE(fs::exists(dir.File("run")));
  r = Attend(dir, {"run", "--images", "img", "--out", "shipped"});
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(Contains(r.err, "feature 'disparity' needs stereo and is left out")) << r.err;
  EXPECT_EQ(Frames(dir, "shipped").size(), 4u);

  r = Attend(dir, {"run", "--images", "img", "--out", "run", "--quiet", "--set",
                   "features.disparity.enabled=false"});
  ASSERT_EQ(r.status, 0) << r.err;
  const std::vector<nlohmann::json> frames = Frames(dir, "run");
  ASSERT_EQ(frames.size(), 4u);
  for (int i = 0; i < 4; ++i) EXPECT_EQ(frames[i]["frame"], i);
  const nlohmann::json summary = nlohmann::json::parse(ReadText(dir.File("run/summary.json")));
  EXPECT_EQ(summary["sequence"]["stereo"], false);
  EXPECT_EQ(summary["sequence"]["name"], "img");
  EXPECT_TRUE(Contains(summary["sequence"]["source"].get<std::string>(), "images ")) << summary;
  // The effective configuration names the folder and repeats the run.
  EXPECT_TRUE(Contains(ReadText(dir.File("run/config.yaml")), "images: \"" + dir.File("img") + "\""))
      << ReadText(dir.File("run/config.yaml"));
  r = Attend(dir, {"run", "--config", "run/config.yaml", "--out", "again", "--quiet"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(Frames(dir, "again").size(), 4u);

  // The objects are attended as in the stereo run; scored with --gt, since a plain folder has
  // no gt/ of its own.
  r = Attend(dir, {"eval", "run"});
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_TRUE(Contains(r.err, "give --gt")) << r.err;
  r = Attend(dir, {"eval", "run", "--gt", "seq/gt"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["coverage"], 1.0) << r.out;

  // Usage and input errors.
  r = Attend(dir, {"run", "--images", "img", "--sequence", "seq"});
  EXPECT_EQ(r.status, 2) << r.err;
  r = Attend(dir, {"run", "--images", "nowhere", "--out", "run2", "--set",
                   "features.disparity.enabled=false"});
  EXPECT_EQ(r.status, 3) << r.err;
  EXPECT_TRUE(Contains(r.err, "images ")) << r.err;
  EXPECT_TRUE(Contains(r.err, "nowhere: no such folder")) << r.err;
  EXPECT_FALSE(fs::exists(dir.File("run2")));
  dir.Write("img/0003.PNG", "broken");
  r = Attend(dir, {"run", "--images", "img", "--out", "run3", "--quiet", "--set",
                   "features.disparity.enabled=false"});
  EXPECT_EQ(r.status, 3) << r.err;
  EXPECT_TRUE(Contains(r.err, "frame 2 (")) << r.err;
  EXPECT_TRUE(Contains(r.err, "0003.PNG): cannot be read or decoded")) << r.err;
}

// Writes every frame of seq/left and seq/right again as one-channel 8-bit PNG, as a grey
// camera delivers them.
void MakeGrey(const testing::TempDir& dir, const std::string& seq) {
  for (const std::string view : {"left", "right"}) {
    for (const fs::directory_entry& entry : fs::directory_iterator(dir.File(seq + "/" + view))) {
      const cv::Mat bgr = cv::imread(entry.path().string(), cv::IMREAD_COLOR);
      cv::Mat grey;
      cv::cvtColor(bgr, grey, cv::COLOR_BGR2GRAY);
      ASSERT_TRUE(cv::imwrite(entry.path().string(), grey));
    }
  }
}

TEST(InputCli, GreyFramesAttendABrightObject) {
  testing::TempDir dir;
  // A bright square and a darker disc on a mid-grey textured wall, all grey.
  dir.Write("grey.yaml",
            "name: grey\nwidth: 320\nheight: 240\nframes: 6\nseed: 5\n"
            "noise: {left: 1.5, right: 1.5}\n"
            "background: {depth: 6.0, colour: [90, 90, 90], texture: 10}\n"
            "objects:\n"
            "  - {id: 1, shape: rectangle, size: [0.5, 0.4], colour: [220, 220, 220], path: "
            "[{frame: 0, x: 210, y: 110, depth: 3.0}], texture: 4}\n");
  Result r = Attend(dir, {"synth", "grey.yaml", "--out", "seq"});
  ASSERT_EQ(r.status, 0) << r.err;
  MakeGrey(dir, "seq");
  ASSERT_EQ(cv::imread(dir.File("seq/left/000000.png"), cv::IMREAD_UNCHANGED).channels(), 1);
  r = Attend(dir, {"run", "--sequence", "seq", "--out", "run", "--quiet", "--set",
                   "output.dump=[features, saliency]"});
  ASSERT_EQ(r.status, 0) << r.err;

  // The colour features carry nothing on grey frames: exactly zero, not stretched noise.
  for (const std::string feature : {"colour_contrast", "skin"}) {
    SCOPED_TRACE(feature);
    const cv::Mat map = ReadPfm(dir.File("run/features/" + feature + "/000000.pfm"));
    EXPECT_EQ(cv::countNonZero(map), 0);
  }
  // The saliency map's peak is on the bright object.
  const std::vector<GtObject> truth = ReadObjectsCsv(dir.File("seq/gt/objects.csv"));
  const cv::Rect object(truth.front().box);
  const cv::Mat saliency = ReadPfm(dir.File("run/saliency/000000.pfm"));
  cv::Point peak;
  cv::minMaxLoc(saliency, nullptr, nullptr, nullptr, &peak);
  EXPECT_TRUE(object.contains(peak)) << peak << " not in " << object;

  // It is attended: a target's box overlaps it in every frame from the first.
  const std::vector<nlohmann::json> frames = Frames(dir, "run");
  ASSERT_EQ(frames.size(), 6u);
  for (int i = 0; i < 6; ++i) {
    SCOPED_TRACE(i);
    EXPECT_GE(BestIou(frames[i], truth[i].box), 0.7);
  }
  r = Attend(dir, {"eval", "run"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["coverage"], 1.0) << r.out;
}

TEST(InputCli, RealOtbFolderRunsWithImages) {
  const std::string img = testing::SharedData() + "/otb/Dog1/img";
  if (!fs::is_directory(img)) GTEST_SKIP() << "reference data not found: " << img;
  testing::TempDir dir;
  const Result r = Attend(dir, {"run", "--images", img, "--frames", "0:4", "--out", "run",
                                "--quiet", "--set", "features.disparity.enabled=false"});
  ASSERT_EQ(r.status, 0) << r.err;
  const std::vector<nlohmann::json> frames = Frames(dir, "run");
  ASSERT_EQ(frames.size(), 5u);
  const nlohmann::json summary = nlohmann::json::parse(ReadText(dir.File("run/summary.json")));
  EXPECT_EQ(summary["pixels"]["input_size"], nlohmann::json({320, 240}));
  for (const nlohmann::json& frame : frames) {
    for (const nlohmann::json& target : frame["targets"]) {
      const cv::Rect box = Box(target);
      EXPECT_LE(box.x + box.width, 320);
      EXPECT_LE(box.y + box.height, 240);
    }
  }
}

}  // namespace
}  // namespace attend
