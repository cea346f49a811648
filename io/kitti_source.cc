#include "io/kitti_source.h"

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "io/frame_files.h"
#include "io/kitti_calibration.h"
#include "io/ranged_source.h"
#include "util/error.h"

namespace attend {

namespace fs = std::filesystem;

namespace {

// The stereo calibration of `sequence` for frames of `size`.
StereoCalibration KittiStereo(const KittiSequence& sequence, cv::Size size) {
  if (sequence.layout == KittiLayout::kRawDrive) {
    // S_rect_02 gives the size; AttachCalibration then checks it against the frames'.
    return ReadKittiRawCalibration(sequence.calibration, cv::Size()).stereo;
  }
  return ReadKittiFrameCalibration(sequence.calibration, size).stereo;
}

class KittiReader final : public NativeReader {
 public:
  KittiReader(const SequenceOptions& options, const KittiSequence& sequence, SequenceInfo* info) {
    const std::string what = options.source.Describe();
    left_files_ = ListFrameFiles(sequence.left_frames, what);
    right_files_ = ListFrameFiles(sequence.right_frames, what);
    if (left_files_.empty()) {
      throw InputError(what + ": no frames in " + sequence.left_frames);
    }
    if (left_files_.size() != right_files_.size()) {
      throw InputError(what + ": " + sequence.left_frames + " has " +
                       std::to_string(left_files_.size()) + " frames but " + sequence.right_frames +
                       " has " + std::to_string(right_files_.size()));
    }
    for (size_t i = 0; i < left_files_.size(); ++i) {
      if (fs::path(left_files_[i]).stem() != fs::path(right_files_[i]).stem()) {
        throw InputError(what + ": " + left_files_[i] + " has no partner of its name in " +
                         sequence.right_frames);
      }
    }
    info->stereo = true;
    info->name = sequence.name;
    info->fps = kKittiFps;
    info->folder = sequence.folder;
    // A --calib file wins (AttachCalibration reads it); KITTI's own otherwise.
    if (options.source.calib.empty()) {
      const cv::Size size = ReadFrameFile(0, left_files_[0]).size();
      info->calibration = std::make_shared<const StereoCalibration>(KittiStereo(sequence, size));
    }
  }

  int Count() const override { return static_cast<int>(left_files_.size()); }

  bool Read(int index, NativeFrame* frame) override {
    if (index < 0 || index >= Count()) return false;
    frame->left_path = left_files_[index];
    frame->left = ReadFrameFile(index, frame->left_path);
    frame->right_path = right_files_[index];
    frame->right = ReadFrameFile(index, frame->right_path);
    return true;
  }

 private:
  std::vector<std::string> left_files_;
  std::vector<std::string> right_files_;
};

}  // namespace

std::unique_ptr<FrameSource> OpenKittiSource(const SequenceOptions& options,
                                             const KittiSequence& sequence) {
  SequenceInfo info;
  auto reader = std::make_unique<KittiReader>(options, sequence, &info);
  return OpenRangedSource(options, std::move(reader), std::move(info));
}

}  // namespace attend
