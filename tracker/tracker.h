// The BIP template tracker (thesis chapter 4, SPEC 2.5).
//
// Every frame, one BIP is built over the union of the targets' regions of interest (ROI) with
// a small T_max (over-segmentation, 4.2.2, 4.3). Each target's template is the regular part of
// its last hierarchical representation: per level, the homogeneous cells of the target with
// their colour, area and weight. From the template's working level (eq. 4.4) down, the
// template is shifted over the ROI's regular cells of the same level, and the displacement with
// the best weighted overlap (eq. 4.5, 4.6) is accepted when the overlap exceeds `min_overlap`
// (4.2.3). The matched cells' regions of the over-segmentation are the target; the target is
// then grown by neighbouring regions of similar colour (4.2.4), the template is updated
// (eq. 4.7, 4.8) and the ROI for the next frame is the target's box plus a border epsilon
// (4.2.6). A target not found is occluded: its weights decay by alpha and its ROI border grows
// by one pixel a frame up to epsilon_max; when every weight reaches 0 it is lost (4.2.7).
#pragma once

#include <memory>
#include <opencv2/core.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "util/option_fields.h"

namespace attend {

// Which tracker: the thesis's as written (chapter 4), or the variant for real footage whose
// refinement and box are bounded (docs/TRACKING.md, "Modes").
enum class TrackerMode { kThesis, kBounded };
// "thesis", "bounded" (the tracker.mode key).
const char* TrackerModeName(TrackerMode mode);
const std::vector<std::string>& TrackerModeNames();
// The mode called `name`; false when there is none.
bool TrackerModeFromName(std::string_view name, TrackerMode* mode);

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
  // sequences. `attend track` and attend.Tracker turn it on (configs/track.yaml).
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

class BipPool;

// Tracks any number of targets in one shared pyramid (4.3). Keeps its buffers between frames.
class MultiTracker {
 public:
  // `pool`: the pool of its pyramids and of its start segmenter (pyramid/bip.h), which must
  // outlive the tracker; nullptr: a pool of its own.
  explicit MultiTracker(TrackerOptions options = {}, BipPool* pool = nullptr);
  ~MultiTracker();
  MultiTracker(const MultiTracker&) = delete;
  MultiTracker& operator=(const MultiTracker&) = delete;

  // Starts a target in `frame` (8-bit BGR) from a mask of its pixels (CV_8UC1, frame size,
  // non-zero = target) or from a box: the box and its surroundings are segmented with the BIP
  // (default options, thesis 4.2.1) and the regions lying mostly inside the box are the target;
  // a skin target from a box is the skin pixels in it. For skin targets `skin` is the frame's
  // binary skin map (CV_8UC1). Returns the new target's id (1, 2, ... in order of starting), or -1
  // when the mask or box holds no usable target (empty, or too thin for a template).
  int StartFromMask(const cv::Mat& frame, const cv::Mat& mask,
                    TrackSimilarity similarity = TrackSimilarity::kColour,
                    const cv::Mat& skin = cv::Mat());
  int StartFromBox(const cv::Mat& frame, const cv::Rect& box,
                   TrackSimilarity similarity = TrackSimilarity::kColour,
                   const cv::Mat& skin = cv::Mat());
  // Starts a target from region `region` of a segmentation of `frame`: `labels` is its label
  // image (CV_32SC1, frame size, as `Segmentation::labels`), and the target is started from the
  // mask of that region's pixels. Returns -1 as StartFromMask does, and for a region without
  // pixels.
  int StartFromRegion(const cv::Mat& frame, const cv::Mat& labels, int region,
                      TrackSimilarity similarity = TrackSimilarity::kColour,
                      const cv::Mat& skin = cv::Mat());

  // Searches every active target in `frame` and appends one result per target, in id order.
  // A target reported lost is removed afterwards. `skin` is needed when a skin target exists.
  // `cylinder`: the frame's BgrToCylinder when the caller has it (it is then not computed
  // again for the regions of interest); the results are the same.
  void Track(const cv::Mat& frame, std::vector<TrackResult>* results,
             const cv::Mat& skin = cv::Mat(), const cv::Mat& cylinder = cv::Mat());

  // The target's pixels in the last frame (CV_8UC1, frame size); empty when it was not found.
  cv::Mat Mask(int id) const;
  // The template weights of a level (for tests and displays): CV_32FC1 over the template's
  // cells of that level, 0 where the template has no vertex; empty for an unknown id or level.
  cv::Mat TemplateWeights(int id, int level) const;
  // Stops tracking a target.
  void Remove(int id);
  // Ids of the targets being tracked.
  std::vector<int> ids() const;
  const TrackerOptions& options() const { return options_; }
  // Milliseconds of the last Track() call, and the part of it spent over-segmenting the ROIs
  // (colour conversion and pyramids; the rest is matching, refinement and template update:
  // the split of thesis tables 4.2 and 4.3).
  double milliseconds() const { return milliseconds_; }
  double segmentation_milliseconds() const { return segmentation_milliseconds_; }

 private:
  struct Impl;
  TrackerOptions options_;
  std::unique_ptr<Impl> impl_;
  double milliseconds_ = 0.0;
  double segmentation_milliseconds_ = 0.0;
};

}  // namespace attend
