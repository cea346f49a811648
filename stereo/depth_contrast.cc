#include "stereo/depth_contrast.h"

#include <algorithm>
#include <opencv2/imgproc.hpp>

#include "util/error.h"

namespace attend {

cv::Mat DepthContrast(const cv::Mat& disparity, const cv::Mat& measured, const GroundPlane& ground,
                      int window) {
  ATTEND_CHECK(disparity.type() == CV_32FC1 && measured.type() == CV_8UC1 &&
               disparity.size() == measured.size() && window >= 3 && window % 2 == 1)
      << "DepthContrast takes a float disparity map, an 8-bit mask of its size and an odd window";
  // Unmeasured pixels take no part in the surround: a value above every disparity.
  constexpr float kUnmeasured = 1e9f;
  constexpr float kMinSurround = 0.5f;
  // The surround is the least value of many: a pixel of the matcher's noise below the rest.
  // Contrast starts beyond it, or a flat wall would be speckled with it.
  constexpr float kMatcherNoise = 1.f;
  cv::Mat far(disparity.size(), CV_32FC1, cv::Scalar(kUnmeasured));
  // Nor do those at the matcher's infinity (under kMinSurround): a sky it measured at 0 would
  // make every nearer pixel around it as salient as can be.
  disparity.copyTo(far, measured & (disparity >= kMinSurround));
  cv::Mat surround;
  // The least disparity in the window: a rectangular erosion, separable in OpenCV.
  cv::erode(far, surround, cv::getStructuringElement(cv::MORPH_RECT, cv::Size(window, window)),
            cv::Point(-1, -1), 1, cv::BORDER_REPLICATE);
  cv::Mat contrast(disparity.size(), CV_32FC1, cv::Scalar(0.f));
  for (int y = 0; y < disparity.rows; ++y) {
    const float* d = disparity.ptr<float>(y);
    const float* s = surround.ptr<float>(y);
    const uint8_t* m = measured.ptr<uint8_t>(y);
    float* out = contrast.ptr<float>(y);
    const float floor = static_cast<float>(ground.valid ? ground.DisparityAt(y) : 0.0);
    for (int x = 0; x < disparity.cols; ++x) {
      if (!m[x] || !(d[x] > 0.f)) continue;
      const float behind = std::max(floor, s[x]);
      out[x] = std::max(0.f, d[x] - behind - kMatcherNoise) / d[x];
    }
  }
  return contrast;
}

}  // namespace attend
