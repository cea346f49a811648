// Whether the tests of live sources can run here: they read real GStreamer pipelines made of
// videotestsrc (gstreamer1.0-plugins-base), through OpenCV's GStreamer backend.
#pragma once

#include <string>

namespace attend::testing {

// "" when OpenCV can read a videotestsrc pipeline; otherwise why not, for GTEST_SKIP.
std::string GstreamerMissing();

// A live pipeline (is-live=true: paced as a camera is) of `buffers` frames (-1: endless) of
// videotestsrc's moving ball, `width` x `height` at `fps` frames a second, ending in an appsink.
std::string TestPipeline(int buffers, int width = 160, int height = 120, int fps = 30);

// A pipeline that gives `frames` frames of 160x120 and then nothing, without ending: a camera
// that stopped delivering. Its frames come through a funnel, which ends its stream only when
// every input has ended, and its second input, a videotestsrc behind an identity that sleeps
// 71 minutes on each buffer, never gives one and never ends.
std::string StallingPipeline(int frames);

}  // namespace attend::testing
