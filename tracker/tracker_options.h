// The options of the BIP template tracker (MultiTracker, tracker/tracker.h) and what it reports
// of each target: its modes, its options with their field table (tracker_options.cc), a
// target's state and result. The tracker's units (roi_pyramid.h, template_search.h, ...)
// include this header, not tracker.h, so that none of them depends on the tracker that
// composes them.
#pragma once

#include <opencv2/core.hpp>
#include <string>

#include "util/option_fields.h"

namespace attend {

// Which tracker: the thesis's as written (chapter 4), the variant for real footage whose
// refinement and box are bounded (docs/TRACKING.md, "Modes"), or the correlation-filter tracker
// whose masks are the BIP's regions (tracker/correlation_tracker.h). The first two are policies
// of MultiTracker, chosen when it is made (tracker_mode.h: thesis_mode.cc, bounded_mode.cc);
// the third is a TargetTracker of its own, made by the bip kind (bip_target_tracker.cc), with
// its options in CorrelationOptions.
enum class TrackerMode { kThesis, kBounded, kCorrelation };
// "thesis", "bounded", "correlation" (the tracker.mode key).
const char* TrackerModeName(TrackerMode mode);

struct TrackerOptions {
  TrackerMode mode = TrackerMode::kThesis;
  float t_colour = 30.f;       // T_c: a template vertex matches a ROI vertex below it (eq. 4.6)
  float t_oversegment = 10.f;  // T_co: T_max of the ROI's over-segmentation
  float t_refine = 20.f;       // T_cr: colour threshold of the target refinement (4.2.4)
  float alpha = 0.1f;          // forgetting constant of the template weights (eq. 4.8)
  // ROI border and its maximum while the target is not found, in pixels at an image width of
  // 128 (the thesis's); scaled by width / 128 (SPEC 2.5).
  float epsilon = 6.f;
  float epsilon_max = 12.f;
  float working_area = 0.8f;  // T_A: share of the template's area at the working level (4.4)
  float min_overlap = 0.7f;   // weighted overlap that accepts a displacement (4.2.3)
  // How the pyramid over the union of the ROIs is built: in independent parts, one per group of
  // nearby ROIs (true), or as one pyramid over the bounding box of every ROI (false). The
  // results are the same; the parts cost what the ROIs cost. Not a thesis parameter: false is
  // there to check the parts against.
  bool pyramid_parts = true;
  // Bounded mode only (TrackerMode::kBounded, docs/TRACKING.md "Modes"): the target may grow
  // by this share of its box's size on each side a frame; the box's size and centre follow the
  // mask's box by this share a frame.
  float bound_growth = 0.05f;
  float size_rate = 0.1f;
  // Bounded mode only: the box's centre follows the mask's box by this share a frame (its size
  // by size_rate): where the target is changes faster than how large it is.
  float centre_rate = 0.3f;
  // Bounded mode only: template weights are scaled by how distinctive their colour is of the
  // target against its surroundings, a table learnt at the start and blended in by this share
  // each frame the target is found; 0 keeps the first frame's table.
  bool distinctive_weights = true;
  float distinct_rate = 0.1f;
  // Bounded mode only: an accepted overlap counts times a Gaussian of its displacement's
  // distance to the previous motion, sigma = this times the box's mean side; 0: off.
  float motion_sigma = 0.5f;
  // Bounded mode only: the weighted overlap that accepts a displacement, in place of
  // `min_overlap` (real footage rarely matches a template by 70 %; the motion prior and the
  // distinctive weights guard a lower bar).
  float bounded_min_overlap = 0.4f;
  // Bounded mode only: the target's grey appearance, a model of its box blended in by
  // `appearance_rate` each frame it is found, is matched by normalised cross-correlation (ZNCC)
  // over the ROI. A displacement then scores the motion prior times
  // (1 - appearance_share) x overlap + appearance_share x max(0, ZNCC), and the best score is
  // accepted above `min_score` (which replaces `bounded_min_overlap`). A target that is not
  // found is searched for by its appearance alone within `redetect_range` box sides of its
  // box, and moves there when it matches by `redetect_ratio` of its typical correlation.
  bool appearance = true;
  float appearance_share = 0.7f;
  float appearance_rate = 0.05f;
  float min_score = 0.3f;
  float redetect_range = 1.5f;
  float redetect_ratio = 0.8f;
  // Bounded mode with appearance, with `occlusion` (docs/TRACKING.md, "Modes" 12): a match
  // whose ZNCC is under `occlusion_gate` of the target's typical correlation moves the box but
  // updates neither the models nor the typical correlation; under `occlusion_ratio` the target
  // is not found in that frame (an occluder or the background took its place), and is searched
  // for by its model as any target not found. While not found, such a target's template
  // forgets at `occlusion_alpha` instead of `alpha`: it survives 1 / occlusion_alpha frames.
  // Off here and in the loop: it lifts the OTB mean success AUC from 0.569 to 0.718 (above
  // CSRT's 0.659) but lowers IDF1 in the attention loop on three of the four still-camera MOT
  // sequences. configs/track.yaml turned it on for `attend track` until issue 42 made its default the correlation mode.
  bool occlusion = false;
  float occlusion_gate = 0.7f;
  float occlusion_ratio = 0.55f;
  float occlusion_alpha = 0.05f;

  // The borders in pixels for images `width` wide (at least 1).
  int EpsilonPixels(int width) const;
  int EpsilonMaxPixels(int width) const;
  // "" when valid; otherwise names the field and the broken constraint.
  std::string Check() const;
  // The fields (util/option_fields.h), which Check and the `tracker` section of
  // the configuration both apply.
  static const OptionFields<TrackerOptions>& Fields();
};

// TrackerOptions with mode = kBounded, the other fields at their defaults.
inline TrackerOptions BoundedTrackerOptions() {
  TrackerOptions options;
  options.mode = TrackerMode::kBounded;
  return options;
}

enum class TrackState { kFound, kOccluded, kLost };
// "found", "occluded", "lost" (the state column of tracks.csv, SPEC 3.2).
const char* TrackStateName(TrackState state);

// How vertices are compared: HSV cylinder colour, or "same skin class" for skin targets (a
// binary skin map passed with each frame; thesis 5.1.2).
enum class TrackSimilarity { kColour, kSkin };

// One target in one frame.
struct TrackResult {
  int id = 0;
  TrackState state = TrackState::kFound;
  cv::Rect box;          // the target's bounding box; the last known one when not found
  cv::Point2f centroid;  // of the target's pixels; the last known one when not found
  int area = 0;          // target pixels this frame (0 when not found)
  int level = -1;        // pyramid level where the template matched; -1 when not found
  double overlap = 0.0;  // the accepted weighted overlap, 0..1; 0 when not found
  cv::Rect roi;          // the region of interest searched this frame
};

}  // namespace attend
