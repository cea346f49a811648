// SEQ/sequence.yaml, the description of a sequence folder (docs/SEQUENCES.md): the input is that
// file of a temporary monocular sequence with one valid 16x12 frame, opened as `attend run
// --sequence SEQ` opens it (OpenFrameSource).
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <string>

#include "fuzz/fuzz_support.h"
#include "io/sequence.h"

namespace {

const std::string& SequenceFolder() {
  static const std::string folder = [] {
    const std::string dir = attend::fuzz::ScratchPath("seq");
    std::filesystem::create_directories(dir + "/left");
    cv::Mat frame(12, 16, CV_8UC3, cv::Scalar(40, 120, 200));
    frame(cv::Rect(4, 3, 6, 5)).setTo(cv::Scalar(250, 20, 90));
    if (!cv::imwrite(dir + "/left/000000.png", frame)) attend::fuzz::Fail("cannot write a frame");
    return dir;
  }();
  return folder;
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  attend::fuzz::Initialize();
  SequenceFolder();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace attend;
  fuzz::WriteFile(SequenceFolder() + "/sequence.yaml", fuzz::ToString(data, size));
  fuzz::ExpectOnlyDocumentedErrors([&] {
    SequenceOptions options;
    options.source.folder = SequenceFolder();
    const std::unique_ptr<FrameSource> source = OpenFrameSource(options);
    StereoFrame frame;
    source->Next(&frame);
  });
  return 0;
}
