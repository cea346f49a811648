// The working size, in one place: the size every source hands its frames out at
// (sequence.width, height, resize), the memory it needs, and the resampling to it. Folders,
// videos and live sources fix it from their first frame (SizeSequence) and bring each frame to
// it (ToWorkingSize); the Python Pipeline and `attend saliency` do the same for their images.
#pragma once

#include <opencv2/core.hpp>

#include "io/frame_source.h"
#include "io/sequence_options.h"

namespace attend {

// The working size of frames of size `native` under `options` (width, height, resize).
cv::Size WorkingSize(const SequenceOptions& options, cv::Size native);

// Sets `info`'s native size to `native` and its working size and scales from `options`.
// A working size whose buffers would not fit in this machine's memory: ConfigError (InputError
// with resize native, the size being the frames').
void SizeSequence(const SequenceOptions& options, cv::Size native, SequenceInfo* info);

// `image` at `size`, continuous: area averaging when shrinking (no aliasing), bilinear when any
// side grows.
cv::Mat ToWorkingSize(const cv::Mat& image, cv::Size size);

}  // namespace attend
