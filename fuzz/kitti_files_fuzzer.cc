// KITTI's text files (io/kitti_tracklets.h, io/kitti_labels.h, io/kitti_calibration.h): the
// input is read as tracklet_labels.xml, as a tracking label_02/NNNN.txt and as a calib/NNNN.txt.
// What reads must hold what the readers promise: tracklets with positive sizes and a frame that
// is not negative, label boxes that do not run backwards, a calibration with a positive focal
// length and baseline.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "fuzz/fuzz_support.h"
#include "io/kitti_calibration.h"
#include "io/kitti_labels.h"
#include "io/kitti_tracklets.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  attend::fuzz::Initialize();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace attend;
  static const std::string input = fuzz::ScratchPath("kitti.txt");
  fuzz::WriteFile(input, fuzz::ToString(data, size));
  fuzz::ExpectOnlyDocumentedErrors([&] {
    for (const KittiTracklet& t : ReadKittiTracklets(input)) {
      if (!(t.h > 0 && t.w > 0 && t.l > 0) || t.first_frame < 0) {
        fuzz::Fail("a tracklet reads with a size that is not positive or a negative frame");
      }
    }
  });
  fuzz::ExpectOnlyDocumentedErrors([&] {
    for (const KittiLabel& label : ReadKittiTrackingLabels(input)) {
      if (label.box.width < 0 || label.box.height < 0 || label.frame < 0) {
        fuzz::Fail("a label reads with a box that runs backwards or a negative frame");
      }
    }
  });
  fuzz::ExpectOnlyDocumentedErrors([&] {
    const KittiRig rig = ReadKittiFrameCalibration(input, cv::Size(1242, 375));
    if (!(rig.stereo.focal_px() > 0 && rig.stereo.baseline_m() > 0)) {
      fuzz::Fail("a calibration reads with a focal length or baseline that is not positive");
    }
  });
  return 0;
}
