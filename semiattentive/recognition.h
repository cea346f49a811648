// Recognition: the top-down channels' detections (features/detectors.h) keep each target on its
// object (not in the thesis). Every frame the found targets and the detections are matched one to
// one; a target matched to a detection is recognised, and:
//   re-anchoring   when its box and the detection's overlap with IoU in
//                  [select.reanchor_min_iou, select.reanchor_max_iou), it starts again from the
//                  detection's seed (semiattentive/seeds.h) under its own id, unless that seed
//                  looks less like the target than select.reanchor_min_similarity (the
//                  detection is someone else's: the target is then not recognised);
//   unrecognised   a labelled target that no detection is on for drop.unrecognised_frames frames
//                  in a row is released;
//   labels         a target takes the label of the detection that overlaps it by at least
//                  label_overlap of the larger box, once, and keeps it.
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "features/feature_map.h"
#include "semiattentive/followed_targets.h"
#include "semiattentive/reidentification.h"
#include "semiattentive/release.h"
#include "semiattentive/seeds.h"
#include "semiattentive/select_options.h"
#include "tracker/target_tracker.h"

namespace attend {

// What recognition makes of a found target in one frame.
struct Recognition {
  int detection = -1;         // the detection it is on (it is recognised); -1: none
  bool reanchor = false;      // its tracker restarts from the detection's seed
  bool unrecognised = false;  // it is released as unrecognised
};

class Recogniser {
 public:
  // `reidentifier` (may be null: the model-free appearance) embeds a detection that a target
  // is re-anchored on, for the look gate.
  Recogniser(const SelectOptions& select, const DropOptions& drop, float label_overlap,
             Reidentifier* reidentifier = nullptr);

  // The detection each of `results` is on (its index, -1: none): the found, non-skin targets and
  // the detections matched one to one (MatchBoxes) at IoU >= select.reanchor_min_iou (0.3 when
  // that is 0), so that a target that drifted cannot take its neighbour's detection from the
  // neighbour's own target. Boxes are clipped to `image`.
  std::vector<int> MatchDetections(const std::vector<TrackResult>& results,
                                   const FollowedTargets& targets,
                                   const std::vector<Detection>& detections,
                                   const cv::Rect& image) const;
  // Recognition of found target `target`, at `box` in `bgr`, matched to detection `detection`
  // (-1: none) of `detections`; updates its recognition counter. The seed to re-anchor on, from
  // the frame's `segmentation`, is made by `seeds` into `seed`.
  Recognition Recognise(const cv::Mat& bgr, const Segmentation& segmentation,
                        const std::vector<Detection>& detections, const cv::Rect& box,
                        int detection, SeedMaker* seeds, FollowedTarget* target, Seed* seed) const;
  // The label of the detection that overlaps `box` most (label_overlap), "" when none does.
  std::string LabelOf(const cv::Rect& box, const std::vector<Detection>& detections) const;

 private:
  SelectOptions select_;
  int unrecognised_frames_;
  float label_overlap_;
  Reidentifier* reidentifier_;
};

}  // namespace attend
