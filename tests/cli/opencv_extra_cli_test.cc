// OpenCV's optional modules (util/opencv_extra.h): attend links only core and imgproc and loads
// libattend_opencv_extra.so when a run asks for a video, an OpenCV tracker, the detectors...;
// a run of image frames never loads it, and a missing module is a clear error.
#include <gtest/gtest.h>
#include <stdlib.h>

#include <cstdio>
#include <filesystem>

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

// Sets an environment variable for the scope (the children attend started inherit it).
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const std::string& value) : name_(name) {
    setenv(name, value.c_str(), 1);
  }
  ~ScopedEnv() { unsetenv(name_); }

 private:
  const char* name_;
};

TEST(OpenCvExtraCli, TheProgramLinksNoneOfTheOptionalModules) {
  FILE* pipe = popen((std::string("ldd ") + ATTEND_BINARY).c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::string libraries;
  char buffer[512];
  while (fgets(buffer, sizeof(buffer), pipe) != nullptr) libraries += buffer;
  pclose(pipe);
  ASSERT_TRUE(Contains(libraries, "libopencv_core")) << libraries;
  // imgcodecs and videoio are still linked (video sources and the video writer), videoio
  // bringing imgcodecs with it.
  for (const char* module : {"video.so", "tracking", "objdetect",
                             "saliency", "dnn", "highgui"}) {
    EXPECT_FALSE(Contains(libraries, std::string("libopencv_") + module)) << libraries;
  }
}

TEST(OpenCvExtraCli, AMissingModuleIsAClearErrorWhereItIsNeeded) {
  testing::TempDir dir;
  const std::string missing = (fs::path(dir.path()) / "nowhere" / "libattend_opencv_extra.so").string();
  const ScopedEnv env("ATTEND_OPENCV_EXTRA", missing);
  const std::string out = (fs::path(dir.path()) / "run").string();
  // A tracker kind of OpenCV's: refused before the run starts, naming the key.
  const std::string sequence =
      testing::MakeFolderSequence((fs::path(dir.path()) / "seq").string(), 3, 64, 48);
  Result r = Attend(dir, {"run", "--sequence", sequence, "--out", out, "--quiet", "--set",
                          "tracker.kind=csrt"});
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_TRUE(Contains(r.err, "tracker.kind csrt needs OpenCV's optional modules")) << r.err;
  EXPECT_TRUE(Contains(r.err, "looked for " + missing)) << r.err;
  EXPECT_FALSE(fs::exists(out)) << "a run that cannot start leaves nothing";

  // A run of PNG frames needs none of it.
  r = Attend(dir, {"run", "--sequence", sequence, "--out", out, "--overwrite", "--quiet"});
  EXPECT_EQ(r.status, 0) << r.err;
}

}  // namespace
}  // namespace attend
