// Reading stereo and monocular sequences (SPEC 3.1): a folder with left/ and right/ (or only
// left/ for monocular), a pair of videos, one side-by-side video, a monocular video, or a plain
// folder of images (monocular, for example an OTB sequence's img/); or live, from a V4L2 camera
// or a GStreamer pipeline (io/live_source.h, docs/LIVE.md).
// Frames come out at the working size, as 8-bit BGR: grey images get three equal channels and
// 16-bit images keep their high byte. docs/SEQUENCES.md describes the layouts and rules.
#pragma once

#include <atomic>
#include <chrono>
#include <memory>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "io/live_options.h"
#include "util/option_fields.h"

namespace attend {

struct SequenceOptions {
  // At most one source may be set; FrameSource::Open needs exactly one.
  std::string folder;      // SEQ: frames in SEQ/left and SEQ/right (monocular without
                           // right/), matched by sorted file name
  std::string left_video;  // with right_video: a pair of videos
  std::string right_video;
  std::string side_by_side_video;  // left half | right half; an odd width is bad input
  std::string video;               // a monocular video
  std::string images;              // DIR: a monocular plain folder of frames, DIR/* matched by
                                   // sorted file name (ListFrameFiles)
  // Live (io/live_source.h): a V4L2 camera /dev/videoN or a GStreamer pipeline; with
  // camera_right or gst_right a stereo pair, with live.side_by_side one side-by-side source.
  int camera = -1;  // N of /dev/videoN; -1: none
  int camera_right = -1;
  std::string gst;  // a pipeline ending in an appsink (one is appended when it has none)
  std::string gst_right;
  LiveOptions live;  // the live section: queue, timeout, duration, side by side

  // Frame range in source indices, inclusive; last_frame = -1 means to the end, and a last_frame
  // beyond the end stops at the end. A range that starts beyond the last frame is bad input.
  int first_frame = 0;
  int last_frame = -1;
  int stride = 1;  // take every stride-th frame from first_frame

  // Working size. "fit": scale, up or down, to the largest size that fits in width x height
  // keeping the aspect ratio (640x480 -> 320x240, 1280x720 -> 320x180, 160x120 -> 320x240);
  // "stretch": exactly width x height; "native": keep the source size.
  int width = 320;
  int height = 240;
  std::string resize = "fit";

  // Empty when valid; otherwise names the field and the broken constraint.
  std::string Check() const;
  // The fields (util/option_fields.h), which Check and the configuration apply; Check applies
  // the ranges of width and height only unless resize is native (the configuration always).
  static const OptionFields<SequenceOptions>& Fields();
  // How many sources are set (a video pair and a live source with its right view count once).
  int SourceCount() const;
  // Whether a live source (camera, gst or their right twins) is set.
  bool IsLive() const;
  // The values of `resize`.
  static const std::vector<std::string>& ResizeModes();
  // A short description of the source for messages: "folder SEQ", "videos A + B", ...
  std::string Describe() const;
};

// The frame files of a folder, in frame order: regular files ending in .png, .jpg, .jpeg, .ppm
// or .pgm (any letter case), sorted by file name byte by byte; everything else is ignored.
// Frame i is the i-th path. `what` starts error messages. InputError when the folder is
// missing, not a folder or cannot be listed; an empty list is not an error here.
std::vector<std::string> ListFrameFiles(const std::string& folder, const std::string& what);

// The file extensions ListFrameFiles accepts, lower case with the dot.
const std::vector<std::string>& FrameFileExtensions();

// Reads frame file `path` as 8-bit BGR (grey gets three equal channels, 16-bit keeps the high
// byte, JPEG EXIF orientation applied). InputError "frame INDEX (PATH): ..." when it cannot be
// read or decoded.
cv::Mat ReadFrameFile(int index, const std::string& path);

// The checks every frame of a source passes: InputError "frame INDEX (PATH): size WxH differs
// from the first frame's ..." when `left` is not of size `first`, or "... differs from the left
// image's ..." when `right` (empty when monocular) is not of the left image's size.
void CheckFrameSizes(int index, const cv::Mat& left, const std::string& left_path,
                     const cv::Mat& right, const std::string& right_path, cv::Size first);

// The working size of frames of size `native` under `options` (width, height, resize).
cv::Size WorkingSize(const SequenceOptions& options, cv::Size native);

// `image` at `size`, continuous: area averaging when shrinking (no aliasing), bilinear when any
// side grows.
cv::Mat ToWorkingSize(const cv::Mat& image, cv::Size size);

// What is known about an opened sequence.
struct SequenceInfo {
  std::string name;  // sequence.yaml name, or the folder/video stem
  bool stereo = true;
  double fps = 25.0;        // sequence.yaml or the video's; 25 when unknown
  double focal_px = 0.0;    // sequence.yaml; 0 when unknown (at the native size)
  double baseline_m = 0.0;  // sequence.yaml; 0 when unknown
  cv::Size native_size;     // size of the source frames (one view)
  cv::Size size;            // working size of the frames handed out
  double scale_x = 1.0;     // size / native_size; disparities scale by scale_x
  double scale_y = 1.0;
  int frame_count = -1;  // frames this source will hand out (range and stride applied);
                         // -1 when a video cannot tell. For videos it comes from the
                         // container's header, which some containers only estimate.
  std::string folder;    // the sequence folder ("" for videos and image folders); gt/ lives
                         // below it
};

struct StereoFrame {
  int index = 0;           // index in the source (before stride), the frame's number
  cv::Mat left;            // CV_8UC3, BGR, working size
  cv::Mat right;           // CV_8UC3, BGR, working size; empty when monocular
  std::string left_path;   // the file, or "VIDEO#index" for videos
  std::string right_path;  // "" when monocular; the same video for side-by-side
  // Live sources: when the frame came out of the source's read (the capture thread's clock);
  // the epoch for files.
  std::chrono::steady_clock::time_point captured{};
};

// A video frame as 8-bit BGR (grey and BGRA converted); InputError "frame INDEX (PATH): ..."
// for other depths or channel counts.
cv::Mat VideoFrameToBgr(const cv::Mat& frame, int index, const std::string& path);

// Sets `info`'s native size to `native` and its working size and scales from `options`.
void SizeSequence(const SequenceOptions& options, cv::Size native, SequenceInfo* info);

class FrameSource {
 public:
  virtual ~FrameSource() = default;

  // Opens a source. A missing folder or file, no frames, left/right counts or sizes that
  // differ: InputError (exit status 3) naming what is wrong. Invalid options: ConfigError.
  static std::unique_ptr<FrameSource> Open(const SequenceOptions& options);

  virtual const SequenceInfo& info() const = 0;

  // The next frame of the range; false at the end. A frame that cannot be decoded or whose
  // size differs from the first frame's throws InputError naming its index and path; frames
  // handed out before stay valid (they never share buffers with later frames), and a further
  // Next() goes on with the frame after the bad one.
  virtual bool Next(StereoFrame* frame) = 0;

  // A source whose Next() may wait for frames (a live one) gives up waiting, and returns
  // false, soon after `*stop` becomes true. Files never wait, and ignore it.
  virtual void WatchStop(const std::atomic<bool>* stop) { (void)stop; }
  // A live source's capture so far (frames captured, dropped, how it ended); nothing for files.
  virtual std::optional<LiveStatus> live_status() const { return std::nullopt; }
};

// `source` read one frame ahead on a thread of its own: while the caller works on a frame, the
// next one is read and decoded (the bundled scene's 320x240 pair: 1.3 ms). The frames, their
// order and the errors (a bad frame's InputError, at the Next() that would have returned it)
// are those of `source`. For files and videos; a live source already has its capture thread.
std::unique_ptr<FrameSource> ReadAhead(std::unique_ptr<FrameSource> source);

}  // namespace attend
