#include "app/track_sequence.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "io/tracking_files.h"
#include "tests/support/temp_dir.h"
#include "util/error.h"

namespace attend {
namespace {

namespace fs = std::filesystem;

// A plain folder of six frames: a red square moving 3 pixels right a frame on grey.
std::string MovingSquare(const testing::TempDir& dir) {
  fs::create_directories(dir.File("img"));
  for (int i = 0; i < 6; ++i) {
    cv::Mat frame(60, 90, CV_8UC3, cv::Scalar(128, 128, 128));
    cv::rectangle(frame, cv::Rect(10 + 3 * i, 20, 16, 16), cv::Scalar(30, 30, 220), cv::FILLED);
    char name[32];
    std::snprintf(name, sizeof(name), "img/%04d.png", i + 1);
    EXPECT_TRUE(cv::imwrite(dir.File(name), frame));
  }
  return dir.File("img");
}

// Counts what it hears.
class Recorder : public TrackObserver {
 public:
  void OnFrame(const StereoFrame& frame, const std::vector<TargetView>& views) override {
    frames.push_back(frame.index);
    boxes.push_back(views.empty() ? cv::Rect() : views[0].box);
  }
  std::vector<int> frames;
  std::vector<cv::Rect> boxes;
};

// One target from `box` on the moving square's frames, written to DIR/out.
TrackRequest Request(const testing::TempDir& dir, const cv::Rect& box) {
  TrackRequest request;
  request.images = MovingSquare(dir);
  request.range_text = "0:";
  request.boxes = {box};
  request.box_texts = {"box 1"};
  request.out = dir.File("out");
  return request;
}

TEST(TrackSequence, TellsObserversEveryFrameAndWritesTheTracks) {
  testing::TempDir dir;
  const TrackRequest request = Request(dir, cv::Rect(8, 18, 20, 20));
  Recorder recorder;
  const std::unique_ptr<TrackObserver> overlays = MakeOverlayDump(request.out);
  const nlohmann::json summary = TrackSequence(request, {&recorder, overlays.get()});

  EXPECT_EQ(summary["frames"], 6);
  EXPECT_EQ(recorder.frames, (std::vector<int>{0, 1, 2, 3, 4, 5}));
  // The box follows the square's centre (x = 18 + 3 i) on every frame.
  for (int i = 0; i < 6; ++i) {
    const cv::Rect& box = recorder.boxes[i];
    EXPECT_NEAR(box.x + box.width / 2.0, 18 + 3 * i, 2.0) << "frame " << i;
    EXPECT_NEAR(box.y + box.height / 2.0, 28, 2.0) << "frame " << i;
  }
  const std::vector<TrackRow> rows = ReadTracksCsv(dir.File("out/tracks.csv"));
  ASSERT_EQ(rows.size(), 6u);
  EXPECT_EQ(rows.back().state, "found");
  EXPECT_TRUE(fs::exists(dir.File("out/overlay/000005.png")));
  EXPECT_TRUE(fs::exists(dir.File("out/track.json")));
}

TEST(TrackSequence, ABoxOutsideTheFrameIsAConfigurationErrorBeforeAnythingIsWritten) {
  testing::TempDir dir;
  const TrackRequest request = Request(dir, cv::Rect(80, 18, 20, 20));
  Recorder recorder;
  try {
    TrackSequence(request, {&recorder});
    FAIL() << "the box does not lie inside the frame";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("box 1 (target 1, frame 0, "), std::string::npos)
        << e.what();
  }
  EXPECT_TRUE(recorder.frames.empty());
  EXPECT_FALSE(fs::exists(dir.File("out")));
}

}  // namespace
}  // namespace attend
