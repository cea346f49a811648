// Motion grouping of object seeds (select.group_min_speed; not in the thesis, whose stage has no
// motion): where a proto-object moves at least group_min_speed px a frame (its colour regions'
// mean dense optical flow from the previous frame, OpenCV's DIS), the colour regions next to it
// that move alike join it, region by region outwards: a region whose mean flow differs from the
// proto-object's by at most group_flow_tolerance times its speed.
#pragma once

#include <memory>
#include <opencv2/core.hpp>
#include <vector>

#include "pyramid/regions.h"
#include "util/opencv_extra.h"

namespace attend {

// Owns the grey frames, the flow between them and its mean per colour region, from one frame to
// the next.
class MotionGrouping {
 public:
  // Loads OpenCV's DIS flow from the optional OpenCV module (util/opencv_extra.h) now, so that a
  // missing module is reported before a run starts.
  MotionGrouping(float min_speed, float flow_tolerance);

  // A new frame (8-bit BGR): the flow is computed when a seed first asks for it.
  void NextFrame(const cv::Mat& bgr);
  // Joins to `members` (colour regions of `segmentation`) the regions next to them that move
  // alike, not `taken`, each at most `max_area`, while `seed_area` stays within it.
  void Group(const Segmentation& segmentation, const std::vector<uint8_t>& taken, double max_area,
             std::vector<int>* members, double* seed_area);

 private:
  // The mean optical flow of each colour region of `segmentation` from the previous frame to
  // this one, once a frame; false when there is no previous frame of the same size.
  bool RegionFlow(const Segmentation& segmentation);
  // Per colour region of `labels`: `region_flow_`, the flow's mean away from the region's
  // border (all of it for a region that is all border).
  void MeanFlowPerRegion(const cv::Mat& labels, size_t regions);

  static constexpr int kFlowBorder = 3;  // px: a region's flow is taken this far inside it
  float min_speed_;
  float flow_tolerance_;
  std::unique_ptr<cvextra::DenseFlow> solver_;
  cv::Mat grey_, previous_grey_, flow_, border_;
  int flow_state_ = 0;  // this frame: 0 not computed yet, 1 computed, -1 none possible
  std::vector<cv::Point2f> region_flow_;
};

}  // namespace attend
