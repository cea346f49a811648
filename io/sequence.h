// Reading stereo and monocular sequences (SPEC 3.1): a folder with left/ and right/ (or only
// left/ for monocular), a pair of videos, one side-by-side video, a monocular video, or a plain
// folder of images (monocular, for example an OTB sequence's img/); or live, from a V4L2 camera
// or a GStreamer pipeline (io/live_source.h, docs/LIVE.md).
// Frames come out at the working size, as 8-bit BGR: grey images get three equal channels and
// 16-bit images keep their high byte. docs/SEQUENCES.md describes the layouts and rules.
//
// This is the top of the frame sources: it opens the source a SequenceOptions describes
// (io/source_spec.h) with the unit of its kind (io/folder_source.h, io/video_source.h,
// io/live_source.h), and brings in what a reader of frames needs besides.
#pragma once

#include <memory>

#include "io/frame_files.h"
#include "io/frame_source.h"
#include "io/read_ahead.h"
#include "io/sequence_options.h"
#include "io/working_size.h"

namespace attend {

// Opens the source of `options`. No source, or invalid options: ConfigError. A missing folder or
// file, no frames, left/right counts or sizes that differ: InputError (exit status 3) naming
// what is wrong.
std::unique_ptr<FrameSource> OpenFrameSource(const SequenceOptions& options);

}  // namespace attend
