// Live sources (docs/LIVE.md): a V4L2 camera (`sequence.camera`, `--camera N`) or a GStreamer
// pipeline (`sequence.gst`, `--gst PIPELINE`) read through OpenCV's cv::VideoCapture, a stereo
// pair of two (`camera_right`, `gst_right`) or one side-by-side source (`live.side_by_side`).
//
// A thread of the source's own reads frames as they come into a queue of `live.queue` frames;
// when the loop is slower than the source the oldest queued frame is dropped and counted, so
// the loop always works on recent frames. A frame's index is its number among the frames read
// from the source (0 the first), so dropped frames leave gaps; `first_frame`, `last_frame` and
// `stride` pick among those numbers as they pick among a file's frames. Every cv::VideoCapture
// of a live source is in live_source.cc; what the source is (its views, how it is described
// and checked) is in io/source_spec.h.
#pragma once

#include <memory>
#include <string>

#include "io/frame_source.h"
#include "io/sequence_options.h"

namespace attend {

// Opens the live source of `options` (options.source.IsLive(), options.Check() empty), starts
// its capture thread and waits for its first frame, which fixes the working size. A camera that
// does not exist or cannot be opened, a pipeline that does not parse or cannot start, a first
// frame that does not come within live.timeout_s: InputError naming the source.
//
// The source's Next() hands out the oldest queued frame, waiting for one; it returns false when
// the source has ended (end of stream, the frame range's last frame, live.duration_s), when no
// frame came for live.timeout_s (the source stopped delivering), or soon after the WatchStop
// flag is set; live_status() says which. A frame of the wrong size (or an odd width,
// side by side) or a failed read: InputError naming the frame. Destroying the source stops its
// thread and joins it; a thread still blocked in a read of a stalled source after a second is
// left to finish on its own (OpenCV's GStreamer backend cannot interrupt a read).
std::unique_ptr<FrameSource> OpenLiveSource(const SequenceOptions& options);

// `pipeline` as OpenCV's GStreamer backend needs it: unchanged when it names an appsink,
// otherwise with " ! videoconvert ! appsink" appended, so that `videotestsrc` or
// `v4l2src device=/dev/video1` works as given.
std::string GstPipelineWithSink(const std::string& pipeline);

}  // namespace attend
