// How well a stereo run's targets know their depth (`attend eval`, issue 44): each target seen
// in a frame (new, tracked, resumed) with a disparity is matched to the ground-truth object its
// box overlaps most, at IoU >= match_iou, among the objects of known disparity visible in that
// frame; over the matches, the disparity's error (pixels of the input frames) and the depth's
// relative error, |Z / Z_true - 1| = |d_true / d - 1| (no calibration needed: Z = f B / d),
// and how often the error lies within one and two of the target's own standard deviations.
#pragma once

#include <vector>

#include "io/frame_record.h"
#include "io/ground_truth.h"

namespace attend {

struct DepthScoreOptions {
  double match_iou = 0.5;
  double min_visible = 0.25;  // an object counts in a frame at this visible fraction or more
  // The depth's relative error is summarised over objects at least this disparity (pixels):
  // farther ones' depths are too uncertain for a percentage to mean much.
  double near_disparity = 8.0;
};

struct DepthScores {
  int matches = 0;                           // (frame, target) pairs with both disparities
  double median_abs_error_px = -1.0;         // -1 when there are no matches
  double mean_abs_error_px = -1.0;
  double share_within_quarter_px = -1.0;     // |error| <= 0.25 px
  int near_matches = 0;                      // of them, objects of disparity >= near_disparity
  double median_depth_error = -1.0;          // relative, over the near matches
  double share_depth_within_2_percent = -1.0;
  double share_within_1_sd = -1.0;           // |error| <= the target's disparity_sd_px
  double share_within_2_sd = -1.0;
};

DepthScores EvaluateTargetDepth(const std::vector<FrameRecord>& frames,
                                const std::vector<GtObject>& truth,
                                const DepthScoreOptions& options = {});

}  // namespace attend
