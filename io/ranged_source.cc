#include "io/ranged_source.h"

#include <algorithm>
#include <optional>
#include <string>
#include <utility>

#include "io/sequence_calibration.h"
#include "io/working_size.h"
#include "util/error.h"

namespace attend {

namespace {

class RangedSource final : public FrameSource {
 public:
  RangedSource(const SequenceOptions& options, std::unique_ptr<NativeReader> reader,
               SequenceInfo info)
      : reader_(std::move(reader)),
        info_(std::move(info)),
        stride_(options.stride),
        next_index_(options.first_frame),
        last_index_(options.last_frame),
        what_(options.source.Describe()) {
    const int count = reader_->Count();
    const std::string& what = what_;
    if (count >= 0 && options.first_frame >= count) {
      throw InputError(what + ": the frame range starts at frame " +
                       std::to_string(options.first_frame) + " but the source has " +
                       std::to_string(count) + " frames (0.." + std::to_string(count - 1) + ")");
    }
    if (count >= 0) {
      last_index_ = last_index_ < 0 ? count - 1 : std::min(last_index_, count - 1);
      info_.frame_count = (last_index_ - options.first_frame) / stride_ + 1;
    } else {
      info_.frame_count = -1;
    }

    // The first frame fixes the native size; it is kept and handed out by the first Next().
    NativeFrame first;
    if (!reader_->Read(options.first_frame, &first)) {
      throw InputError(what + ": there is no frame " + std::to_string(options.first_frame) +
                       " (the source is empty or the frame range starts beyond its end)");
    }
    SizeSequence(options, first.left.size(), &info_);
    CheckSizes(options.first_frame, first);
    rectifier_ = AttachCalibration(options, &info_);
    first_ = std::move(first);
  }

  const SequenceInfo& info() const override { return info_; }

  bool Next(StereoFrame* frame) override {
    ATTEND_CHECK(frame != nullptr) << "Next needs a frame to fill";
    if (finished_) return false;
    const int index = next_index_;
    if (last_index_ >= 0 && index > last_index_) {
      finished_ = true;
      return false;
    }
    // Moving on before reading lets a caller that catches a bad frame continue after it.
    next_index_ += stride_;
    NativeFrame native;
    if (first_.has_value()) {
      native = std::move(*first_);
      first_.reset();
    } else if (!reader_->Read(index, &native)) {
      finished_ = true;
      // The source announced its length (a video's header): ending before it means frames
      // are missing, a file cut short most often. The frames before were delivered, and the
      // run keeps them; this one is an error, not a quiet end.
      if (reader_->Count() >= 0 && index < reader_->Count()) {
        throw InputError(what_ + ": ends at frame " + std::to_string(index) +
                         ", but it announces " + std::to_string(reader_->Count()) + " frames (0.." +
                         std::to_string(reader_->Count() - 1) +
                         "); the file may be cut short (the frames before were read; if its "
                         "header miscounts, set sequence.last_frame)");
      }
      return false;
    }
    CheckSizes(index, native);
    // A raw pair is rectified at its native size, before the working size.
    if (rectifier_ != nullptr && !native.right.empty()) {
      rectifier_->Apply(&native.left, &native.right);
    }
    frame->index = index;
    frame->left = ToWorkingSize(native.left, info_.size);
    frame->right = native.right.empty() ? cv::Mat() : ToWorkingSize(native.right, info_.size);
    frame->left_path = std::move(native.left_path);
    frame->right_path = std::move(native.right_path);
    return true;
  }

 private:
  void CheckSizes(int index, const NativeFrame& frame) const {
    CheckFrameSizes(index, frame.left, frame.left_path, frame.right, frame.right_path,
                    info_.native_size);
  }

  std::unique_ptr<NativeReader> reader_;
  SequenceInfo info_;
  int stride_;
  int next_index_;
  int last_index_;    // inclusive; -1 while the end is unknown
  std::string what_;  // the source, for messages
  bool finished_ = false;
  std::optional<NativeFrame> first_;
  std::shared_ptr<const Rectifier> rectifier_;  // a full calibration's; null otherwise
};

}  // namespace

std::unique_ptr<FrameSource> OpenRangedSource(const SequenceOptions& options,
                                              std::unique_ptr<NativeReader> reader,
                                              SequenceInfo info) {
  return std::make_unique<RangedSource>(options, std::move(reader), std::move(info));
}

}  // namespace attend
