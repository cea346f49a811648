// OTB ground-truth box files (groundtruth_rect.txt), read by `attend eval-tracking --gt` and
// the tracking benchmark: the input is the file, read with ReadOtbGroundTruth. Boxes that read
// are scored as eval-tracking scores them (ScoreTracking): against themselves, against boxes
// shifted by 10 px, and with no prediction at all.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "fuzz/fuzz_support.h"
#include "eval/tracking_scores.h"
#include "io/tracking_files.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  attend::fuzz::Initialize();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace attend;
  static const std::string input = fuzz::ScratchPath("groundtruth_rect.txt");
  fuzz::WriteFile(input, fuzz::ToString(data, size));
  fuzz::ExpectOnlyDocumentedErrors([&] {
    const std::vector<cv::Rect2d> truth = ReadOtbGroundTruth(input);
    std::vector<cv::Rect2d> shifted = truth;
    for (cv::Rect2d& box : shifted) box.x += 10.0;
    const std::vector<cv::Rect2d>* predictions[] = {&truth, &shifted};
    for (const std::vector<cv::Rect2d>* predicted : predictions) {
      const TrackingScores scores = ScoreTracking(*predicted, truth);
      if (scores.frames > static_cast<int>(truth.size())) {
        fuzz::Fail("ScoreTracking counts more frames than the ground truth has");
      }
    }
    ScoreTracking({}, truth);
  });
  return 0;
}
