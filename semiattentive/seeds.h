// Seeds: what a candidate of the attention stage starts a target from (select.seed; thesis
// 5.1.2 for the colour region):
//   region     the colour region of the frame's segmentation that the candidate overlaps most,
//              unless a target holds it or it is larger than select.max_area_fraction of the
//              image (background)
//   object     that region with every colour region of which at least select.seed_share lies
//              in the candidate's salient region (the connected area around its most salient
//              pixel where the inhibited saliency is at least select.seed_level times the
//              candidate's mean), bounded as a region is; then, with select.group_min_speed,
//              the neighbours that move alike (semiattentive/motion_grouping.h)
//   detection  where the candidate's most salient pixel lies in a top-down detection's box: the
//              colour regions of which at least select.seed_share lies inside the box, clipped
//              to it (a whole person); a detection a target is on, or that a followed target
//              covers by select.detection_taken, starts nothing; elsewhere an object seed, or
//              nothing with select.detected_only
#pragma once

#include <map>
#include <opencv2/core.hpp>
#include <vector>

#include "features/feature_map.h"
#include "pyramid/regions.h"
#include "semiattentive/background.h"
#include "semiattentive/candidates.h"
#include "semiattentive/motion_grouping.h"
#include "semiattentive/select_options.h"

namespace attend {

struct Seed {
  int best = -1;             // the colour region under the candidate
  std::vector<int> members;  // the colour regions it takes, `best` first
  double area = 0.0;         // its pixels
  int detection = -1;        // the detection it was made from; -1: none
  // A detection seed's pixels (CV_8UC1, frame size, 255 on the seed), clipped to the detection's
  // box: the SeedMaker's buffer, valid until it makes its next seed. Empty for the others.
  cv::Mat mask;
};

// What the seeds of one frame's candidates are made against. The flags of the regions taken
// (under.taken) and of the detections used change as the frame's targets start.
struct SeedFrame {
  const Segmentation& segmentation;
  const cv::Mat& inhibited;  // the inhibited saliency (CV_32FC1)
  const Candidates& candidates;
  const CandidateRegions& under;  // the colour regions under the candidates, and those taken
  const std::vector<Detection>& detections;
  const std::vector<uint8_t>& detection_used;  // per detection: a target is on it
  const std::vector<cv::Rect>& followed;       // the boxes of the targets followed now
  double max_area;                             // select.max_area_fraction of the image
  // The frame's background and region depths (select.background); nullptr: off.
  const SceneAnalysis* scene = nullptr;
};

// Makes seeds; keeps the masks they are painted in between frames.
class SeedMaker {
 public:
  explicit SeedMaker(const SelectOptions& options) : options_(options) {}

  // The seed of ranked candidate `k` into `seed`; false when it starts nothing. `grouping`:
  // motion grouping of object seeds (nullptr: off).
  bool Make(const SeedFrame& frame, size_t k, MotionGrouping* grouping, Seed* seed);
  // The seed of detection `index` of `frame` on its own (select.every_detection), as a
  // candidate's detection seed is made, but not bounded by select.max_area_fraction (the box
  // is one object, however near); false when a target is on it, a followed target covers it
  // or its seed is smaller than select.min_area.
  bool FromDetection(const SeedFrame& frame, int index, Seed* seed);
  // The seed of a detected object in `box`: the colour regions of `segmentation` of which at
  // least select.seed_share lies inside the box, clipped to it, into seed->mask; seed->area
  // gets its pixels and seed->members the regions (after those it holds).
  void FromBox(const Segmentation& segmentation, const cv::Rect& box, Seed* seed);
  // The pixels of colour regions `members` of `segmentation` (CV_8UC1, 255 on them): the
  // maker's buffer, valid until its next seed.
  const cv::Mat& MaskOf(const Segmentation& segmentation, const std::vector<int>& members);

 private:
  // The object seed (`seed`, its best region only) grown to the proto-object around ranked
  // candidate region `r`.
  void GrowObject(const SeedFrame& frame, int r, MotionGrouping* grouping, Seed* seed);

  SelectOptions options_;
  cv::Mat mask_;                 // a seed's pixels
  cv::Mat fill_;                 // the flood fill of an object seed's salient region
  std::vector<uint8_t> member_;  // per colour region: in the seed
};

}  // namespace attend
