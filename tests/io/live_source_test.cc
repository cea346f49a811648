// Live sources (io/live_source.h) on real GStreamer pipelines of videotestsrc: frames arrive in
// order with their capture times, a slow reader loses the oldest frames and the counts say so,
// pairs and side-by-side frames, the frame range, a source that stalls, the stop flag, and bad
// sources refused quickly. Each test skips when OpenCV cannot read videotestsrc.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <thread>

#include "io/live_source.h"
#include "io/sequence.h"
#include "tests/support/gstreamer.h"
#include "util/error.h"

namespace attend {
namespace {

using Clock = std::chrono::steady_clock;

double SecondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}


#define SKIP_WITHOUT_GSTREAMER()                                          \
  do {                                                                    \
    const std::string missing = testing::GstreamerMissing();              \
    if (!missing.empty()) GTEST_SKIP() << "no GStreamer here: " << missing; \
  } while (false)

TEST(LiveSource, FramesArriveInOrderWithTheirCaptureTimes) {
  SKIP_WITHOUT_GSTREAMER();
  SequenceOptions options;
  options.source.gst = testing::TestPipeline(10);
  options.source.live.queue = 16;  // room for every frame: none is dropped
  std::unique_ptr<FrameSource> source = OpenFrameSource(options);
  const SequenceInfo& info = source->info();
  EXPECT_FALSE(info.stereo);
  EXPECT_EQ(info.native_size, cv::Size(160, 120));
  EXPECT_EQ(info.size, cv::Size(320, 240));  // fit in the default box
  EXPECT_EQ(info.fps, 30.0);
  EXPECT_EQ(info.frame_count, -1);
  EXPECT_EQ(info.name, "gst");
  StereoFrame frame;
  int frames = 0;
  Clock::time_point previous{};
  while (source->Next(&frame)) {
    EXPECT_EQ(frame.index, frames);
    EXPECT_EQ(frame.left.size(), cv::Size(320, 240));
    EXPECT_EQ(frame.left.type(), CV_8UC3);
    EXPECT_TRUE(frame.right.empty());
    EXPECT_EQ(frame.left_path, "gst#" + std::to_string(frames));
    EXPECT_GT(frame.captured, previous);
    EXPECT_LE(frame.captured, Clock::now());
    previous = frame.captured;
    ++frames;
  }
  EXPECT_EQ(frames, 10);
  const std::optional<LiveStatus> status = source->live_status();
  ASSERT_TRUE(status.has_value());
  EXPECT_EQ(status->captured, 10);
  EXPECT_EQ(status->dropped, 0);
  EXPECT_EQ(status->unprocessed, 0);
  EXPECT_EQ(status->end, LiveEnd::kEndOfStream);
  EXPECT_NE(status->why.find("end of stream after 10 frames"), std::string::npos) << status->why;
  EXPECT_FALSE(source->Next(&frame));
}

TEST(LiveSource, ASlowReaderLosesTheOldestFramesAndCountsThem) {
  SKIP_WITHOUT_GSTREAMER();
  SequenceOptions options;
  // 300 frames a second, far faster than this reader, which takes 20 ms a frame.
  options.source.gst = testing::TestPipeline(60, 160, 120, 300);
  options.source.live.queue = 2;
  std::unique_ptr<FrameSource> source = OpenFrameSource(options);
  StereoFrame frame;
  std::vector<int> indices;
  while (source->Next(&frame)) {
    indices.push_back(frame.index);
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  const std::optional<LiveStatus> status = source->live_status();
  ASSERT_TRUE(status.has_value());
  EXPECT_EQ(status->captured, 60);
  EXPECT_GT(status->dropped, 0);
  EXPECT_EQ(static_cast<int>(indices.size()) + status->dropped, 60);
  // The newest frames are kept: the last one is always handed out, and the gaps are the
  // dropped frames.
  ASSERT_FALSE(indices.empty());
  EXPECT_EQ(indices.back(), 59);
  int gaps = 0;
  for (size_t i = 1; i < indices.size(); ++i) {
    EXPECT_GT(indices[i], indices[i - 1]);
    gaps += indices[i] - indices[i - 1] - 1;
  }
  EXPECT_EQ(gaps + indices.front(), status->dropped);
}

TEST(LiveSource, AStereoPairOfTwoPipelines) {
  SKIP_WITHOUT_GSTREAMER();
  SequenceOptions options;
  options.source.gst = testing::TestPipeline(5);
  options.source.gst_right = testing::TestPipeline(5);
  options.source.live.queue = 8;
  std::unique_ptr<FrameSource> source = OpenFrameSource(options);
  EXPECT_TRUE(source->info().stereo);
  EXPECT_EQ(source->info().name, "gst-gst");
  StereoFrame frame;
  int frames = 0;
  while (source->Next(&frame)) {
    EXPECT_EQ(frame.right.size(), frame.left.size());
    EXPECT_EQ(frame.right_path, "gst_right#" + std::to_string(frame.index));
    ++frames;
  }
  EXPECT_EQ(frames, 5);
  EXPECT_NE(options.source.Describe().find(" + GStreamer pipeline '"), std::string::npos);
}

TEST(LiveSource, SideBySideFramesAreSplitIntoTheTwoViews) {
  SKIP_WITHOUT_GSTREAMER();
  SequenceOptions options;
  options.source.gst = testing::TestPipeline(3, 320, 120);
  options.source.live.side_by_side = true;
  options.resize = "native";
  std::unique_ptr<FrameSource> source = OpenFrameSource(options);
  EXPECT_TRUE(source->info().stereo);
  EXPECT_EQ(source->info().native_size, cv::Size(160, 120));
  StereoFrame frame;
  ASSERT_TRUE(source->Next(&frame));
  EXPECT_EQ(frame.left.size(), cv::Size(160, 120));
  EXPECT_EQ(frame.right.size(), cv::Size(160, 120));
  EXPECT_TRUE(frame.left.isContinuous());
  EXPECT_TRUE(frame.right.isContinuous());
  EXPECT_EQ(frame.right_path, frame.left_path);
  EXPECT_EQ(options.source.Describe().rfind("side-by-side GStreamer pipeline", 0), 0u);
}

TEST(LiveSource, TheFrameRangeAndStrideCountTheFramesRead) {
  SKIP_WITHOUT_GSTREAMER();
  SequenceOptions options;
  options.source.gst = testing::TestPipeline(-1);  // endless: the range ends it
  options.first_frame = 2;
  options.last_frame = 8;
  options.stride = 3;
  options.source.live.queue = 8;
  std::unique_ptr<FrameSource> source = OpenFrameSource(options);
  StereoFrame frame;
  std::vector<int> indices;
  while (source->Next(&frame)) indices.push_back(frame.index);
  EXPECT_EQ(indices, (std::vector<int>{2, 5, 8}));
  EXPECT_EQ(source->live_status()->end, LiveEnd::kFrameRange);
  EXPECT_EQ(source->live_status()->captured, 3);
}

TEST(LiveSource, DurationEndsTheCapture) {
  SKIP_WITHOUT_GSTREAMER();
  SequenceOptions options;
  options.source.gst = testing::TestPipeline(-1);
  options.source.live.duration_s = 0.5;
  options.source.live.queue = 64;
  const Clock::time_point start = Clock::now();
  std::unique_ptr<FrameSource> source = OpenFrameSource(options);
  StereoFrame frame;
  int frames = 0;
  while (source->Next(&frame)) ++frames;
  EXPECT_LT(SecondsSince(start), 3.0);
  EXPECT_EQ(source->live_status()->end, LiveEnd::kDuration);
  // 30 frames a second for half a second, give or take a loaded machine's scheduling.
  EXPECT_GE(frames, 5);
  EXPECT_LE(frames, 20);
}

TEST(LiveSource, ASourceThatStopsDeliveringEndsAfterTheTimeout) {
  SKIP_WITHOUT_GSTREAMER();
  SequenceOptions options;
  options.source.gst = testing::StallingPipeline(3);
  options.source.live.timeout_s = 0.5;
  options.source.live.queue = 4;
  const Clock::time_point start = Clock::now();
  {
    std::unique_ptr<FrameSource> source = OpenFrameSource(options);
    StereoFrame frame;
    for (int i = 0; i < 3; ++i) ASSERT_TRUE(source->Next(&frame));
    const Clock::time_point waited = Clock::now();
    EXPECT_FALSE(source->Next(&frame));
    EXPECT_GE(SecondsSince(waited), 0.45);
    const std::optional<LiveStatus> status = source->live_status();
    EXPECT_EQ(status->end, LiveEnd::kTimeout);
    EXPECT_NE(status->why.find("delivered no frame for 0.5 s"), std::string::npos) << status->why;
    EXPECT_EQ(status->captured, 3);
  }
  // Closing does not wait for the stalled read: the thread is left to end alone.
  EXPECT_LT(SecondsSince(start), 5.0);
}

TEST(LiveSource, TheStopFlagEndsTheWaitForAFrame) {
  SKIP_WITHOUT_GSTREAMER();
  SequenceOptions options;
  options.source.gst = testing::StallingPipeline(1);
  options.source.live.timeout_s = 60;
  std::unique_ptr<FrameSource> source = OpenFrameSource(options);
  std::atomic<bool> stop = false;
  source->WatchStop(&stop);
  StereoFrame frame;
  ASSERT_TRUE(source->Next(&frame));
  std::thread stopper([&stop] {
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    stop = true;
  });
  const Clock::time_point start = Clock::now();
  EXPECT_FALSE(source->Next(&frame));
  stopper.join();
  EXPECT_LT(SecondsSince(start), 2.0);
  EXPECT_EQ(source->live_status()->end, LiveEnd::kStopped);
}

TEST(LiveSource, APipelineThatDoesNotParseIsBadInputAtOnce) {
  SKIP_WITHOUT_GSTREAMER();
  for (const std::string pipeline :
       {"videotestsrc ! nosuchelement ! appsink", "videotestsrc ! appsink ! ("}) {
    SCOPED_TRACE(pipeline);
    SequenceOptions options;
    options.source.gst = pipeline;
    const Clock::time_point start = Clock::now();
    try {
      OpenFrameSource(options);
      ADD_FAILURE() << "opened";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("GStreamer pipeline '" + pipeline +
                                           "': cannot be opened"),
                std::string::npos)
          << e.what();
    }
    EXPECT_LT(SecondsSince(start), 3.0);
  }
}

TEST(LiveSource, AFirstFrameThatDoesNotComeIsBadInput) {
  SKIP_WITHOUT_GSTREAMER();
  SequenceOptions options;
  options.source.gst = testing::StallingPipeline(1);
  options.first_frame = 1;  // the stalling pipeline has no second frame
  options.source.live.timeout_s = 0.5;
  const Clock::time_point start = Clock::now();
  try {
    OpenFrameSource(options);
    ADD_FAILURE() << "opened";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no frame within 0.5 s (live.timeout_s)"),
              std::string::npos)
        << e.what();
  }
  EXPECT_LT(SecondsSince(start), 4.0);
}

TEST(LiveSource, APipelineThatNeverStartsIsBadInputAfterTheTimeout) {
  SKIP_WITHOUT_GSTREAMER();
  // GStreamer makes what it can of this (no element "this") and OpenCV then waits for ever for
  // it to play; the source gives up after live.timeout_s.
  SequenceOptions options;
  options.source.gst = "this is not a pipeline";
  options.source.live.timeout_s = 1;
  const Clock::time_point start = Clock::now();
  try {
    OpenFrameSource(options);
    ADD_FAILURE() << "opened";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("GStreamer pipeline 'this is not a pipeline': did not "
                                         "start within 1 s (live.timeout_s)"),
              std::string::npos)
        << e.what();
  }
  EXPECT_LT(SecondsSince(start), 4.0);
}

TEST(LiveSource, ACameraThatDoesNotExistIsBadInputAtOnce) {
  // No GStreamer needed: V4L2.
  SequenceOptions options;
  options.source.camera = 97;
  const Clock::time_point start = Clock::now();
  try {
    OpenFrameSource(options);
    ADD_FAILURE() << "opened";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("camera 97: no such device /dev/video97"),
              std::string::npos)
        << e.what();
  }
  EXPECT_LT(SecondsSince(start), 3.0);
}

TEST(LiveSource, InconsistentLiveKeysAreRefused) {
  auto problem = [](auto change) {
    SequenceOptions options;
    change(&options);
    return options.Check();
  };
  EXPECT_EQ(problem([](SequenceOptions* o) { o->source.camera = 0; }), "");
  EXPECT_EQ(problem([](SequenceOptions* o) { o->source.gst = "v4l2src"; o->source.camera_right = 1; }), "");
  EXPECT_NE(problem([](SequenceOptions* o) { o->source.camera_right = 1; })
                .find("camera_right needs camera or gst for the left view"),
            std::string::npos);
  EXPECT_NE(problem([](SequenceOptions* o) {
              o->source.camera = 0;
              o->source.gst = "v4l2src";
            }).find("camera and gst are both set"),
            std::string::npos);
  EXPECT_NE(problem([](SequenceOptions* o) {
              o->source.camera = 0;
              o->source.camera_right = 0;
            }).find("the same device 0"),
            std::string::npos);
  EXPECT_NE(problem([](SequenceOptions* o) {
              o->source.gst = "a";
              o->source.gst_right = "b";
              o->source.live.side_by_side = true;
            }).find("live.side_by_side reads both views from one source"),
            std::string::npos);
  EXPECT_NE(problem([](SequenceOptions* o) {
              o->source.video = "v.avi";
              o->source.live.duration_s = 3;
            }).find("live.duration_s bounds a live source"),
            std::string::npos);
  EXPECT_NE(problem([](SequenceOptions* o) {
              o->source.video = "v.avi";
              o->source.camera = 0;
            }).find("at most one source"),
            std::string::npos);
  EXPECT_NE(problem([](SequenceOptions* o) {
              o->source.camera = 0;
              o->source.live.queue = 0;
            }).find("live.queue"),
            std::string::npos);
  SequenceOptions pair;
  pair.source.camera = 0;
  pair.source.camera_right = 1;
  EXPECT_EQ(pair.source.SourceCount(), 1);
  EXPECT_EQ(pair.source.Describe(), "camera 0 + camera 1");
}

TEST(LiveSource, AnAppsinkIsAppendedToAPipelineWithoutOne) {
  EXPECT_EQ(GstPipelineWithSink("videotestsrc"), "videotestsrc ! videoconvert ! appsink");
  EXPECT_EQ(GstPipelineWithSink("v4l2src device=/dev/video1 ! "),
            "v4l2src device=/dev/video1 ! videoconvert ! appsink");
  EXPECT_EQ(GstPipelineWithSink("videotestsrc ! appsink name=s"), "videotestsrc ! appsink name=s");
  EXPECT_EQ(GstPipelineWithSink("videotestsrc ! appsink"), "videotestsrc ! appsink");
  // An element whose name only contains the word is not an appsink.
  EXPECT_EQ(GstPipelineWithSink("videotestsrc ! myappsinkish"),
            "videotestsrc ! myappsinkish ! videoconvert ! appsink");
}

TEST(LiveSource, DefaultsAreValid) {
  EXPECT_EQ(CheckFieldRanges(LiveOptions(), LiveOptions::Fields()), "");
  EXPECT_EQ(SequenceOptions().Check(), "");
}

}  // namespace
}  // namespace attend
