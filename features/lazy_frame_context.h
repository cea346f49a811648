// The frame context the pipeline hands the feature plugins (features/frame_context.h): it holds
// the frame and lazily computes, once per frame, what several plugins share: the HSV cylinder
// and TSL images, the skin distance map of each skin model asked for (the skin feature and
// the attention stage's skin targets), the frame's BIP colour segmentation with its region
// adjacency graph, and the disparity map for each DisparityOptions asked for. The lazy getters are safe to call from several plugins at once; the first
// caller computes, the others wait and then share the result.
//
// One context serves a whole stream of frames: Reset() starts a frame and keeps every buffer,
// so after the first frame nothing is allocated (unless someone else still holds one:
// util/shared_mat.h).
#pragma once

#include <list>
#include <memory>
#include <mutex>
#include <opencv2/core.hpp>

#include "colour/skin_model.h"
#include "features/frame_context.h"
#include "pyramid/segmentation.h"
#include "stereo/ground_plane.h"

namespace attend {

// The disparity estimators of one frame context or of several that share them: each estimator
// keeps its buffers from frame to frame (the cost volume: tens of MB at 640x480 with D = 64),
// so the two contexts of a pipeline that works on two frames at once share one
// (pipeline/frame_pipeline.h) instead of holding two. Thread-safe: calls with the same options
// wait for each other.
class DisparityEstimators {
 public:
  // The disparity of the pair by the estimator of `options` (made on first use) into `out`, and
  // where it was measured (DisparityEstimator::measured) into `measured`.
  void Compute(const DisparityOptions& options, const cv::Mat& left, const cv::Mat& right,
               cv::Mat* out, cv::Mat* measured);

 private:
  struct Entry {
    explicit Entry(const DisparityOptions& options) : estimator(options) {}
    std::mutex mutex;  // guards the estimator's buffers while it computes
    DisparityEstimator estimator;
  };
  std::mutex mutex_;         // guards the list
  std::list<Entry> entries_;  // a list, so that entries stay where they are
};

class LazyFrameContext final : public FrameContext {
 public:
  // `pool`: the segmentation's pyramid pool (pyramid/bip.h); nullptr: its own. `estimators`:
  // the disparity's, shared with other contexts; nullptr: its own.
  explicit LazyFrameContext(const SegmentationOptions& segmentation = {}, BipPool* pool = nullptr,
                            std::shared_ptr<DisparityEstimators> estimators = nullptr);

  // Starts a frame: `left` (and `right`, empty when monocular) are 8-bit BGR images of the
  // same size. The images are referenced, not copied; they must outlive the frame.
  void Reset(int frame_index, const cv::Mat& left, const cv::Mat& right = cv::Mat());
  // The options of the run's disparity (FrameContext::disparity_options); the defaults until
  // set. The pipeline sets those of the `disparity` feature's entry.
  void set_disparity_options(const DisparityOptions& options) { disparity_options_ = options; }

  int frame_index() const override { return frame_index_; }
  const cv::Mat& left() const override { return left_; }
  const cv::Mat& right() const override { return right_; }

  // The left image as HSV cylinder (CV_32FC3: S cos H, S sin H, V) and as TSL (CV_32FC3: T,
  // S, L); colour/colour.h.
  const cv::Mat& Cylinder() const override;
  const cv::Mat& Tsl() const override;
  // The squared Mahalanobis distance of the left image's chrominance to `model`'s mean
  // (CV_32FC1, SkinDistanceMap of Tsl()), once per frame for each model (by its mean and
  // covariance). The reference stays valid until the next Reset.
  const cv::Mat& SkinDistance(const SkinModel& model) const override;
  // The BIP colour segmentation of the left image: labels, region statistics, adjacency graph.
  const Segmentation& Regions() const override;
  // The disparity of the stereo pair by DisparityEstimator with `options`, once per frame for
  // each options (each keeps its estimator and buffers between frames).
  const cv::Mat& Disparity(const DisparityOptions& options) const override;
  const DisparityOptions& disparity_options() const override { return disparity_options_; }
  // Where Disparity(options) measured a disparity (CV_8UC1, 255 where it did: the left-right
  // check passed on a textured window; DisparityEstimator::measured). Not part of the plugin
  // API: the built-in disparity feature and the attention stage read it.
  const cv::Mat& DisparityMeasured(const DisparityOptions& options) const;
  // The ground plane of Disparity(options) over its measured pixels (stereo/ground_plane.h),
  // fitted once a frame for the disparity feature and the attention stage's background.
  const GroundPlane& DisparityGround(const DisparityOptions& options) const;
  // Where attention looks (FrameContext::AttentionRegions); Reset keeps them, the pipeline
  // sets them for each frame before its features run.
  const std::vector<cv::Rect>& AttentionRegions() const override { return attention_regions_; }
  void set_attention_regions(std::vector<cv::Rect> regions) {
    attention_regions_ = std::move(regions);
  }

 private:
  // One lazily computed value: `ready` is guarded by `mutex`.
  struct Slot {
    std::mutex mutex;
    bool ready = false;
  };

  int frame_index_ = -1;
  std::vector<cv::Rect> attention_regions_;
  cv::Mat left_;
  cv::Mat right_;

  mutable Slot cylinder_slot_;
  mutable Slot tsl_slot_;
  mutable Slot regions_slot_;
  mutable cv::Mat cylinder_;
  mutable cv::Mat tsl_;
  // One skin distance map per model asked for; a list, so that references stay valid.
  struct SkinSlot {
    Eigen::Vector2d mean;
    Eigen::Matrix2d covariance;
    bool ready = false;
    cv::Mat distance;
  };
  mutable std::mutex skin_mutex_;
  mutable std::list<SkinSlot> skin_slots_;
  // One disparity map per options asked for; a list, so that references stay valid.
  struct DisparitySlot {
    DisparityOptions options;
    bool ready = false;
    cv::Mat disparity;
    cv::Mat measured;
    bool ground_ready = false;
    GroundPlane ground;
  };
  mutable std::mutex disparity_mutex_;
  mutable std::list<DisparitySlot> disparity_slots_;
  // The slot of `options`, computed on first use in the frame.
  DisparitySlot& DisparitySlotOf(const DisparityOptions& options) const;
  std::shared_ptr<DisparityEstimators> estimators_;
  DisparityOptions disparity_options_;
  mutable Segmenter segmenter_;
  mutable Segmentation regions_;
};

}  // namespace attend
