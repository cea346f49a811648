// Video sources (docs/SEQUENCES.md): a pair of videos (left_video + right_video), one
// side-by-side video (the left view in its left half) or one monocular video, read through
// OpenCV's videoio (util/opencv_extra.h). A frame's path is "VIDEO#index".
#pragma once

#include <memory>

#include "io/frame_source.h"
#include "io/sequence_options.h"

namespace attend {

// The video source of `options.source` (a pair, side by side or monocular). InputError when a
// video is missing or cannot be decoded, or the two of a pair announce different lengths; a
// frame later: when the views of a pair end apart, a side-by-side width is odd, or the video
// ends before the length it announced.
std::unique_ptr<FrameSource> OpenVideoSource(const SequenceOptions& options);

}  // namespace attend
