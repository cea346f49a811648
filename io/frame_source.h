// The interface every frame source hands its frames out through (io/sequence.h opens one):
// what is known about the sequence, and its frames, one by one, at the working size as 8-bit
// BGR. Folders and images (io/folder_source.h), videos (io/video_source.h) and live input
// (io/live_source.h) implement it; ReadAhead (io/read_ahead.h) wraps one.
#pragma once

#include <atomic>
#include <chrono>
#include <memory>
#include <opencv2/core.hpp>
#include <optional>
#include <string>

#include "io/live_options.h"
#include "io/stereo_calibration.h"

namespace attend {

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
  // The stereo calibration (io/stereo_calibration.h): SEQ/calib.yaml, --calib FILE
  // (sequence.calib), or sequence.yaml's focal_px and baseline_m; null when there is none or
  // the source is monocular. For the native size: frames handed out are rectified already
  // when it rectifies (a raw pair), and scale_x, scale_y take its pixels to the working size.
  std::shared_ptr<const StereoCalibration> calibration;
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

class FrameSource {
 public:
  virtual ~FrameSource() = default;

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

}  // namespace attend
