// A detector's boxes linked into tracks, frame to frame: the detector-alone peer of `attend run`
// (`attend track-detections`, app/track_detections.h; docs/ATTENTION.md, "The detector-alone
// peer"). Not in the thesis: it is what attention is measured against, the same detector with
// the simplest tracking-by-detection on top (the IoU tracker of Bochinski et al. 2017 with a
// constant-velocity prediction and a one-to-one assignment, as SORT does without a Kalman
// filter).
//
// Each frame:
//   1. every live track predicts its box: its last box moved by its velocity times the frames
//      since it was last matched. The velocity is the mean displacement a frame of its box's
//      centre over its last `velocity_frames` matched frames (the last matched box's centre
//      minus the centre `velocity_frames` matches before, over the frames between them; fewer
//      matches: from its first). The size is the last box's. A track matched once does not move.
//   2. tracks and detections are paired one to one by the minimum-cost assignment on
//      1 - IoU(prediction, detection), pairs below `match_iou` excluded (util/assignment.h,
//      MatchBoxes): as many pairs as there can be, then the least summed cost;
//   3. a paired track takes the detection's box (not its prediction); an unpaired detection
//      starts a track under a new id; a track left unpaired for more than `max_missed`
//      consecutive frames ends, and its id is never used again.
// Frames are counted by calls to Link: one a frame processed.
#pragma once

#include <deque>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "util/option_fields.h"

namespace attend {

struct DetectionLinkOptions {
  double match_iou = 0.3;   // a track and a detection pair only at IoU >= this
  int max_missed = 30;      // a track unmatched for more than this many frames in a row ends
  int velocity_frames = 5;  // the velocity's span, in matched frames; 0: no prediction
  // "" when valid; otherwise names the field and the broken constraint.
  std::string Check() const;
  static const OptionFields<DetectionLinkOptions>& Fields();
};

// One detection of a frame and the track it was linked to.
struct LinkedBox {
  int id = 0;            // the track's id, 1, 2, ... in the order tracks start
  cv::Rect box;          // the detection's box
  bool started = false;  // the track's first frame
  int detection = -1;    // the detection's index in the frame's list
};

class DetectionLinker {
 public:
  explicit DetectionLinker(const DetectionLinkOptions& options);

  // Links one frame's detections: one LinkedBox a detection, in the detections' order.
  std::vector<LinkedBox> Link(const std::vector<cv::Rect>& detections);

  // Tracks started so far (the last id given), and those alive after the last Link.
  int tracks_started() const { return next_id_ - 1; }
  int live_tracks() const { return static_cast<int>(tracks_.size()); }

 private:
  struct Track {
    int id = 0;
    // Its last matched boxes with the frames they were matched in, oldest first: at most
    // velocity_frames + 1.
    std::deque<std::pair<int, cv::Rect2d>> seen;
  };
  // Where `track` is expected in frame `frame`.
  cv::Rect2d Predict(const Track& track, int frame) const;

  DetectionLinkOptions options_;
  std::vector<Track> tracks_;
  int frame_ = -1;  // the frame of the last Link
  int next_id_ = 1;
};

}  // namespace attend
