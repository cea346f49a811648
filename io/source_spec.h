// What a frame source is, described once (docs/SEQUENCES.md, docs/LIVE.md): a sequence folder, a
// pair of videos, a side-by-side video, a monocular video, a plain folder of images, or a live
// camera or GStreamer pipeline with the `live:` settings it is read with. The configuration's
// `sequence:` keys (SequenceOptions::source), `attend run`'s flags, attend.run's keywords and
// the sweeps' inputs all fill this one struct; io/sequence.h opens it.
#pragma once

#include <string>
#include <vector>

#include "io/live_options.h"
#include "util/option_fields.h"

namespace attend {

// The kinds of source, one for each way the fields below can be set.
enum class SourceKind {
  kNone,
  kFolder,      // folder
  kVideoPair,   // left_video + right_video
  kSideBySide,  // side_by_side_video
  kVideo,       // video
  kImages,      // images
  kLive,        // camera or gst, with their right twins or live.side_by_side
};

struct SourceSpec {
  // At most one source may be set; opening needs exactly one.
  std::string folder;      // SEQ: frames in SEQ/left and SEQ/right (monocular without
                           // right/), matched by sorted file name; or a KITTI raw drive
                           // or tracking sequence (io/kitti_layout.h)
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
  // The stereo calibration of the source (io/sequence_calibration.h): a calib.yaml that wins
  // over SEQ/calib.yaml; "" for none. Not a source of its own: SourceCount ignores it.
  std::string calib;
  LiveOptions live;  // the live section: queue, timeout, duration, side by side

  // The source fields (util/option_fields.h), the configuration's sequence.folder ...
  // sequence.gst_right and sequence.calib; `live` has its own table (LiveOptions::Fields).
  static const OptionFields<SourceSpec>& Fields();

  // How many sources are set (a video pair and a live source with its right view count once).
  int SourceCount() const;
  bool empty() const { return SourceCount() == 0; }
  // Whether a live source (camera, gst or their right twins) is set.
  bool IsLive() const;
  // The kind set; kNone when none is (or, for a source that fails Check(), the first set).
  SourceKind Kind() const;
  // The file and folder paths that are set (calib too), to be made absolute by a caller that
  // stores them.
  std::vector<std::string*> Paths();

  // Empty when valid (also when no source is set); otherwise names the keys and what is wrong.
  // CheckKinds: one kind, a whole video pair, the field ranges; CheckLive: the live section's
  // ranges and the live keys' consistency. Check: both. SequenceOptions::Check runs its own
  // ranges between the two, so that errors come in the order of the keys.
  std::string Check() const;
  std::string CheckKinds() const;
  std::string CheckLive() const;

  // A short description for messages and summary.json: "folder SEQ", "videos A + B",
  // "camera 0 + camera 1", ...; "no source" when none is set.
  std::string Describe() const;
};

// One view of a live source: a camera or a pipeline.
struct LiveView {
  int camera = -1;
  std::string gst;
  std::string key;  // the pipeline's key, for frame names: "gst" or "gst_right"

  bool empty() const { return camera < 0 && gst.empty(); }
  // "camera 0", "GStreamer pipeline 'videotestsrc'".
  std::string Describe() const;
  // What names its frames, as a file names a folder's: "/dev/video0#12", "gst#12".
  std::string FrameStem() const;
  // Its part of the sequence name: "camera0", "gst".
  std::string Name() const;
};

LiveView LeftView(const SourceSpec& spec);
LiveView RightView(const SourceSpec& spec);
// Whether the live source of `spec` gives stereo frames: a right view, or one side-by-side
// source.
bool LiveIsStereo(const SourceSpec& spec);

}  // namespace attend
