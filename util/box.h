// Overlap of two axis-aligned boxes, the measure every matcher of attend uses (the MOTChallenge
// and OTB criterion): intersection over union.
#pragma once

#include <opencv2/core.hpp>

namespace attend {

// |a ∩ b| / |a ∪ b| of the boxes as rectangles of their type (pixels for cv::Rect, continuous
// for cv::Rect2d); 0 when the union is empty.
template <typename T>
double BoxIou(const cv::Rect_<T>& a, const cv::Rect_<T>& b) {
  const double shared = static_cast<double>((a & b).area());
  const double joined = static_cast<double>(a.area()) + static_cast<double>(b.area()) - shared;
  return joined > 0.0 ? shared / joined : 0.0;
}

}  // namespace attend
