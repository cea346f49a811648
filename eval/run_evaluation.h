// The attention metrics of SPEC 4 for a run against ground-truth objects (`attend eval`).
//
// A target is on an object in a frame when its box and the object's visible box overlap with
// IoU >= `match_iou` (the object with the largest IoU wins); only targets that are new or
// tracked in that frame count. An object counts when it is visible (visible_fraction >=
// `min_visible`, box area >= `min_area`) in at least one frame of the run.
//   coverage           objects attended (some target on them while visible) / objects
//   latency            frames from an object's first visible frame to its first attention,
//                      mean over attended objects
//   revisits           new targets that start on an object another active target was already
//                      on (inhibition-of-return failures)
//   identity switches  changes of the target on an object between the frames it has one
//   mean IoU           over every (frame, target on an object)
// With disparity ground truth and dumped disparity maps, also the mean bad-pixel rates.
#pragma once

#include <string>
#include <vector>

#include "io/ground_truth.h"
#include "io/frame_record.h"

namespace attend {

struct EvaluationOptions {
  double match_iou = 0.3;
  double min_visible = 0.25;
  double min_area = 64.0;
};

struct ObjectScore {
  int id = 0;
  std::string kind;
  int first_visible = -1;   // frame
  int first_attended = -1;  // frame, -1 when never
  int switches = 0;
};

struct AttentionScores {
  int frames = 0;
  int objects = 0;
  int attended = 0;
  double coverage = 0.0;
  double mean_latency = 0.0;  // frames
  int revisits = 0;
  int identity_switches = 0;
  double mean_iou = 0.0;
  int matches = 0;  // (frame, target) pairs on an object
  std::vector<ObjectScore> per_object;
};

AttentionScores EvaluateAttention(const std::vector<FrameRecord>& frames,
                                  const std::vector<GtObject>& truth,
                                  const EvaluationOptions& options = {});

}  // namespace attend
