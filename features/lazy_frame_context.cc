#include "features/lazy_frame_context.h"

#include <algorithm>

#include "colour/colour.h"
#include "features/skin.h"
#include "util/error.h"
#include "util/shared_mat.h"

namespace attend {

void DisparityEstimators::Compute(const DisparityOptions& options, const cv::Mat& left,
                                  const cv::Mat& right, cv::Mat* out, cv::Mat* measured) {
  Entry* entry = nullptr;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    for (Entry& candidate : entries_) {
      if (candidate.estimator.options() == options) entry = &candidate;
    }
    if (entry == nullptr) entry = &entries_.emplace_back(options);
  }
  const std::lock_guard<std::mutex> lock(entry->mutex);
  entry->estimator.Compute(left, right, out);
  entry->estimator.measured().copyTo(*measured);
}

LazyFrameContext::LazyFrameContext(const SegmentationOptions& segmentation, BipPool* pool,
                                   std::shared_ptr<DisparityEstimators> estimators)
    : estimators_(estimators != nullptr ? std::move(estimators)
                                        : std::make_shared<DisparityEstimators>()),
      segmenter_(segmentation, pool) {}

void LazyFrameContext::Reset(int frame_index, const cv::Mat& left, const cv::Mat& right) {
  ATTEND_CHECK(!left.empty() && left.type() == CV_8UC3) << "the left image must be 8-bit BGR";
  ATTEND_CHECK(right.empty() || (right.type() == CV_8UC3 && right.size() == left.size()))
      << "the right image must be 8-bit BGR of the left image's size";
  frame_index_ = frame_index;
  left_ = left;
  right_ = right;
  // Only the calling thread runs Reset, between frames; no plugin is computing.
  cylinder_slot_.ready = false;
  tsl_slot_.ready = false;
  regions_slot_.ready = false;
  for (SkinSlot& slot : skin_slots_) slot.ready = false;
  for (DisparitySlot& slot : disparity_slots_) slot.ready = false;
  // A buffer of the last frame that someone still holds (a Python feature's array) is let go,
  // so that this frame does not overwrite it (util/shared_mat.h).
  ReleaseIfShared(&cylinder_);
  ReleaseIfShared(&tsl_);
  ReleaseIfShared(&regions_.labels);
  for (SkinSlot& slot : skin_slots_) ReleaseIfShared(&slot.distance);
  for (DisparitySlot& slot : disparity_slots_) {
    ReleaseIfShared(&slot.disparity);
    ReleaseIfShared(&slot.measured);
  }
}

const cv::Mat& LazyFrameContext::Cylinder() const {
  std::lock_guard<std::mutex> lock(cylinder_slot_.mutex);
  if (!cylinder_slot_.ready) {
    BgrToCylinder(left_, &cylinder_);
    cylinder_slot_.ready = true;
  }
  return cylinder_;
}

const cv::Mat& LazyFrameContext::Tsl() const {
  std::lock_guard<std::mutex> lock(tsl_slot_.mutex);
  if (!tsl_slot_.ready) {
    BgrToTsl(left_, &tsl_);
    tsl_slot_.ready = true;
  }
  return tsl_;
}

const cv::Mat& LazyFrameContext::SkinDistance(const SkinModel& model) const {
  std::lock_guard<std::mutex> lock(skin_mutex_);
  auto slot = std::find_if(skin_slots_.begin(), skin_slots_.end(), [&](const SkinSlot& s) {
    return s.mean == model.mean && s.covariance == model.covariance;
  });
  if (slot == skin_slots_.end()) {
    SkinSlot added;
    added.mean = model.mean;
    added.covariance = model.covariance;
    slot = skin_slots_.insert(skin_slots_.end(), std::move(added));
  }
  if (!slot->ready) {
    // From the TSL image when someone asked for it, else a row at a time from the frame: the
    // same values, without the whole frame's TSL.
    bool have_tsl = false;
    {
      const std::lock_guard<std::mutex> tsl_lock(tsl_slot_.mutex);
      have_tsl = tsl_slot_.ready;
    }
    if (have_tsl) {
      SkinDistanceMap(tsl_, model, &slot->distance);
    } else {
      SkinDistanceMapOfBgr(left_, model, &slot->distance);
    }
    slot->ready = true;
  }
  return slot->distance;
}

const cv::Mat& LazyFrameContext::Disparity(const DisparityOptions& options) const {
  return DisparitySlotOf(options).disparity;
}

const cv::Mat& LazyFrameContext::DisparityMeasured(const DisparityOptions& options) const {
  return DisparitySlotOf(options).measured;
}

LazyFrameContext::DisparitySlot& LazyFrameContext::DisparitySlotOf(
    const DisparityOptions& options) const {
  ATTEND_CHECK(stereo()) << "the disparity needs a stereo frame (frame " << frame_index_ << ")";
  std::lock_guard<std::mutex> lock(disparity_mutex_);
  auto slot = std::find_if(disparity_slots_.begin(), disparity_slots_.end(),
                           [&](const DisparitySlot& s) { return s.options == options; });
  if (slot == disparity_slots_.end()) {
    slot = disparity_slots_.insert(disparity_slots_.end(), DisparitySlot{options});
  }
  if (!slot->ready) {
    estimators_->Compute(options, left_, right_, &slot->disparity, &slot->measured);
    slot->ready = true;
    slot->ground_ready = false;
  }
  return *slot;
}

const GroundPlane& LazyFrameContext::DisparityGround(const DisparityOptions& options) const {
  DisparitySlot& slot = DisparitySlotOf(options);
  std::lock_guard<std::mutex> lock(disparity_mutex_);
  if (!slot.ground_ready) {
    slot.ground = FitGroundPlane(slot.disparity, slot.measured);
    slot.ground_ready = true;
  }
  return slot.ground;
}

const Segmentation& LazyFrameContext::Regions() const {
  const cv::Mat& cylinder = Cylinder();
  std::lock_guard<std::mutex> lock(regions_slot_.mutex);
  if (!regions_slot_.ready) {
    segmenter_.SegmentCylinder(cylinder, &regions_);
    // The pyramid's levels go back to the shared pool for the tracker's and the saliency's
    // pyramids; the segmentation is all the frame needs of it.
    segmenter_.ReleasePyramid();
    regions_slot_.ready = true;
  }
  return regions_;
}

}  // namespace attend
