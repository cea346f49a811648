#include "tests/support/gstreamer.h"

#include <opencv2/videoio.hpp>
#include <opencv2/videoio/registry.hpp>

namespace attend::testing {

std::string GstreamerMissing() {
  static const std::string missing = [] {
    if (!cv::videoio_registry::hasBackend(cv::CAP_GSTREAMER)) {
      return std::string("OpenCV has no GStreamer backend");
    }
    cv::VideoCapture capture;
    if (!capture.open(TestPipeline(1), cv::CAP_GSTREAMER)) {
      return std::string("OpenCV cannot read a videotestsrc pipeline (is "
                         "gstreamer1.0-plugins-base installed?)");
    }
    cv::Mat frame;
    if (!capture.read(frame) || frame.empty()) {
      return std::string("a videotestsrc pipeline gives no frame");
    }
    return std::string();
  }();
  return missing;
}

std::string TestPipeline(int buffers, int width, int height, int fps) {
  return "videotestsrc pattern=ball is-live=true num-buffers=" + std::to_string(buffers) +
         " ! video/x-raw,width=" + std::to_string(width) +
         ",height=" + std::to_string(height) + ",framerate=" + std::to_string(fps) +
         "/1 ! videoconvert ! appsink";
}

std::string StallingPipeline(int frames) {
  const std::string caps = "video/x-raw,width=160,height=120,framerate=30/1";
  return "funnel name=f ! videoconvert ! appsink videotestsrc pattern=ball num-buffers=" +
         std::to_string(frames) + " ! " + caps + " ! f. videotestsrc ! " + caps +
         " ! identity sleep-time=4000000000 ! f.";
}

}  // namespace attend::testing
