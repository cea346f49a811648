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
#include <vector>

#include "tracker/tracker_options.h"

namespace attend {

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
