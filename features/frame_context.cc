#include "features/frame_context.h"

#include "colour/colour.h"
#include "util/error.h"

namespace attend {

FrameContext::FrameContext(const SegmentationOptions& segmentation) : segmenter_(segmentation) {}

void FrameContext::Reset(int frame_index, const cv::Mat& left, const cv::Mat& right) {
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
}

const cv::Mat& FrameContext::Cylinder() const {
  std::lock_guard<std::mutex> lock(cylinder_slot_.mutex);
  if (!cylinder_slot_.ready) {
    BgrToCylinder(left_, &cylinder_);
    cylinder_slot_.ready = true;
  }
  return cylinder_;
}

const cv::Mat& FrameContext::Tsl() const {
  std::lock_guard<std::mutex> lock(tsl_slot_.mutex);
  if (!tsl_slot_.ready) {
    BgrToTsl(left_, &tsl_);
    tsl_slot_.ready = true;
  }
  return tsl_;
}

const Segmentation& FrameContext::Regions() const {
  const cv::Mat& cylinder = Cylinder();
  std::lock_guard<std::mutex> lock(regions_slot_.mutex);
  if (!regions_slot_.ready) {
    segmenter_.SegmentCylinder(cylinder, &regions_);
    regions_slot_.ready = true;
  }
  return regions_;
}

}  // namespace attend
