#include "semiattentive/release.h"

namespace attend {

const OptionFields<DropOptions>& DropOptions::Fields() {
  using O = DropOptions;
  static const OptionFields<DropOptions> fields = {
      {"min_saliency", &O::min_saliency, Range::Closed(0, 1),
       "a target below this uninhibited saliency for `frames` frames is released"},
      {"frames", &O::frames, Range::Closed(1, 1e6), "frames of low saliency before release"},
      {"max_shared", &O::max_shared, Range::Closed(0, 1),
       "a target more of whose mask older targets hold is a duplicate; 1: never"},
      {"unrecognised_frames", &O::unrecognised_frames, Range::Closed(0, 1e6),
       "a labelled target no detection overlapped this many frames is released; 0: never"}};
  return fields;
}

ReleaseRules::ReleaseRules(const SelectOptions& select, const DropOptions& drop)
    : max_area_fraction_(select.max_area_fraction),
      min_area_(select.min_area),
      min_saliency_(drop.min_saliency),
      frames_(drop.frames),
      max_shared_(drop.max_shared) {}

int ReleaseRules::LowFrames(double saliency, int low_frames) const {
  return saliency < min_saliency_ ? low_frames + 1 : 0;
}

ReleaseReason ReleaseRules::WhyReleased(const cv::Rect& box, int area, int low_frames,
                                        double shared, const cv::Rect& image) const {
  if (area > max_area_fraction_ * image.area()) return ReleaseReason::kTooLarge;
  if (box.width >= kSpansImageFraction * image.width &&
      box.height >= kSpansImageFraction * image.height) {
    return ReleaseReason::kSpansImage;
  }
  if (box.area() < min_area_) return ReleaseReason::kTooSmall;
  if (low_frames >= frames_) return ReleaseReason::kLowSaliency;
  if (shared > max_shared_) return ReleaseReason::kDuplicate;
  return ReleaseReason::kNone;
}

void HeldPixels::Reset(cv::Size size) {
  held_.create(size, CV_8UC1);
  held_.setTo(0);
}

double HeldPixels::Shared(const cv::Mat& mask, int area) const {
  return static_cast<double>(cv::countNonZero(held_ & mask)) / area;
}

}  // namespace attend
