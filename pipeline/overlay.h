// The overlay a person watches: the left image with each target's box and id in a colour
// that stays the same for that id, and the order in which targets were attended.
#pragma once

#include <opencv2/core.hpp>

#include "pipeline/frame_record.h"

namespace attend {

// A colour per target id, far apart for consecutive ids (golden-angle hue steps).
cv::Scalar TargetColour(int id);

// Draws `record` over a copy of `left` (8-bit BGR).
cv::Mat DrawOverlay(const cv::Mat& left, const FrameRecord& record);

}  // namespace attend
