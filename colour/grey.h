// Grey frames: images without colour, as grey cameras (EuRoC) and grey JPEGs (OTB Dog1) give
// them once read as BGR (io/sequence.h gives grey images three equal channels).
#pragma once

#include <opencv2/core.hpp>

namespace attend {

// True when every pixel of the 8-bit BGR image has three equal channels: saturation (SPEC 2.1)
// and TSL chrominance are then 0 everywhere, so colour features have nothing to measure. An
// empty image is not grey.
bool IsGreyImage(const cv::Mat& bgr);

}  // namespace attend
