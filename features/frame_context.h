// What a feature plugin sees of a frame (SPEC 1, 2.3; docs/PLUGINS.md): the images, their colour
// planes, each skin model's distance map, the frame's colour segmentation (labels, region
// statistics, region adjacency graph; pyramid/regions.h) and, from a stereo source, the
// disparity. It is an interface: its layout does
// not depend on how the values are computed (features/lazy_frame_context.h is the pipeline's),
// so the pyramid's internals can change without changing what plugins are built against
// (ATTEND_PLUGIN_ABI_VERSION, features/plugin_api.h).
//
// Every getter may be called from several plugins at once; a value is computed once a frame,
// by its first caller. A reference stays valid until the frame ends.
#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "colour/skin_model.h"
#include "pyramid/regions.h"
#include "stereo/disparity.h"

namespace attend {

class FrameContext {
 public:
  virtual ~FrameContext() = default;
  FrameContext(const FrameContext&) = delete;
  FrameContext& operator=(const FrameContext&) = delete;

  // The frame's index in its sequence.
  virtual int frame_index() const = 0;
  // The left and right images (8-bit BGR, one size); `right` is empty for a monocular source.
  virtual const cv::Mat& left() const = 0;
  virtual const cv::Mat& right() const = 0;
  bool stereo() const { return !right().empty(); }
  cv::Size size() const { return left().size(); }

  // The left image as HSV cylinder (CV_32FC3: S cos H, S sin H, V) and as TSL (CV_32FC3: T,
  // S, L); colour/colour.h.
  virtual const cv::Mat& Cylinder() const = 0;
  virtual const cv::Mat& Tsl() const = 0;
  // The squared Mahalanobis distance of the left image's chrominance to `model`'s mean
  // (CV_32FC1; features/skin.h SkinDistanceMap), once a frame for each model.
  virtual const cv::Mat& SkinDistance(const SkinModel& model) const = 0;
  // The colour segmentation of the left image: labels, region statistics, adjacency graph.
  virtual const Segmentation& Regions() const = 0;
  // The disparity map of the stereo pair (CV_32FC1, in pixels, on the left image's grid;
  // stereo/disparity.h) computed with `options`, once a frame for each options asked for: the
  // `disparity` feature and a plugin that asks with the same options share one computation.
  // Only for a stereo source (stereo(); a plugin that needs it says so with NeedsStereo).
  virtual const cv::Mat& Disparity(const DisparityOptions& options) const = 0;
  // The options of the run's disparity: those of the `disparity` feature's entry when the run
  // enables it, else DisparityOptions's defaults. Disparity(disparity_options()) is the map
  // that feature uses.
  virtual const DisparityOptions& disparity_options() const = 0;
  // Where attention looks in this frame, in the frame's pixels: a box around each target the
  // attention stage follows (where it was last seen, or where its object file predicts it) and
  // around each candidate it weighed in the previous frame, clipped to the frame. A top-down
  // channel gated by attention (`gate: attended`, features/detectors.h) looks only here.
  // Empty on a sequence's first frame and for still images.
  virtual const std::vector<cv::Rect>& AttentionRegions() const = 0;

 protected:
  FrameContext() = default;
};

}  // namespace attend
