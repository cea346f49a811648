// OpenCV's optional modules (util/opencv_extra.h): attend links only core and imgproc and loads
// libattend_opencv_extra.so when a run asks for a video, an OpenCV tracker, the detectors...;
// a run of image frames never loads it, and a missing module is a clear error.
#include <gtest/gtest.h>
#include <stdlib.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include "tests/cli/attend_cli.h"
#include "tests/support/attend_process.h"
#include "tests/support/scoped_env.h"
#include "tests/support/sequence_maker.h"
#include "tests/support/temp_dir.h"

namespace fs = std::filesystem;

namespace attend {
namespace {

using testing::Attend;
using testing::Contains;
using testing::ReadText;
using testing::Result;

// A short Motion-JPEG video of a coloured square moving on a grey background.
std::string MakeVideo(const testing::TempDir& dir) {
  const std::string path = (fs::path(dir.path()) / "moving.avi").string();
  cv::VideoWriter writer(path, cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), 10.0,
                         cv::Size(160, 120));
  EXPECT_TRUE(writer.isOpened());
  for (int i = 0; i < 12; ++i) {
    cv::Mat frame(120, 160, CV_8UC3, cv::Scalar(120, 120, 120));
    cv::rectangle(frame, cv::Rect(20 + 4 * i, 40, 30, 30), cv::Scalar(30, 40, 220), cv::FILLED);
    writer.write(frame);
  }
  return path;
}

using testing::ScopedEnv;

TEST(OpenCvExtraCli, TheProgramLinksNoneOfTheOptionalModules) {
  FILE* pipe = popen((std::string("ldd ") + ATTEND_BINARY).c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::string libraries;
  char buffer[512];
  while (fgets(buffer, sizeof(buffer), pipe) != nullptr) libraries += buffer;
  pclose(pipe);
  ASSERT_TRUE(Contains(libraries, "libopencv_core")) << libraries;
  for (const char* module : {"imgcodecs", "videoio", "video.so", "tracking", "objdetect",
                             "saliency", "dnn", "highgui"}) {
    EXPECT_FALSE(Contains(libraries, std::string("libopencv_") + module)) << libraries;
  }
}

TEST(OpenCvExtraCli, AVideoRunWithAnOpenCvTrackerLoadsTheModule) {
  testing::TempDir dir;
  const std::string video = MakeVideo(dir);
  const std::string out = (fs::path(dir.path()) / "run").string();
  const Result r = Attend(dir, {"run", "--video", video, "--out", out, "--quiet", "--set",
                                "features=[{name: colour_contrast}]", "--set", "tracker.kind=kcf",
                                "--set", "output.video=true"});
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string frames = ReadText(out + "/frames.jsonl");
  EXPECT_EQ(std::count(frames.begin(), frames.end(), '\n'), 12);
  EXPECT_TRUE(Contains(frames, "\"state\":\"new\"")) << frames;  // a target was started
  std::error_code error;
  EXPECT_GT(fs::file_size(out + "/overlay.avi", error), 0u) << error.message();
}

TEST(OpenCvExtraCli, AMissingModuleIsAClearErrorWhereItIsNeeded) {
  testing::TempDir dir;
  const std::string video = MakeVideo(dir);
  const std::string missing = (fs::path(dir.path()) / "nowhere" / "libattend_opencv_extra.so").string();
  const ScopedEnv env("ATTEND_OPENCV_EXTRA", missing);
  const std::string out = (fs::path(dir.path()) / "run").string();
  Result r = Attend(dir, {"run", "--video", video, "--out", out, "--quiet", "--set",
                          "features=[{name: colour_contrast}]"});
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_TRUE(Contains(r.err, "attend: error: video " + video +
                                  " needs OpenCV's optional modules")) << r.err;
  EXPECT_TRUE(Contains(r.err, "looked for " + missing)) << r.err;
  EXPECT_FALSE(fs::exists(out)) << "a run that cannot start leaves nothing";

  // A tracker kind of OpenCV's: refused before the run starts, naming the key.
  const std::string sequence =
      testing::MakeFolderSequence((fs::path(dir.path()) / "seq").string(), 3, 64, 48);
  r = Attend(dir, {"run", "--sequence", sequence, "--out", out, "--quiet", "--set",
                   "tracker.kind=csrt"});
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_TRUE(Contains(r.err, "tracker.kind csrt needs OpenCV's optional modules")) << r.err;

  // A run of PNG frames needs none of it.
  r = Attend(dir, {"run", "--sequence", sequence, "--out", out, "--overwrite", "--quiet"});
  EXPECT_EQ(r.status, 0) << r.err;
}

}  // namespace
}  // namespace attend
