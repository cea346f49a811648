#include "colour/grey.h"

namespace attend {

bool IsGreyImage(const cv::Mat& bgr) {
  CV_Assert(bgr.empty() || bgr.type() == CV_8UC3);
  if (bgr.empty()) return false;
  for (int y = 0; y < bgr.rows; ++y) {
    const uchar* pixel = bgr.ptr<uchar>(y);
    for (int x = 0; x < bgr.cols; ++x, pixel += 3) {
      // Colour frames usually fail on their first pixels, so this stops early for them.
      if (pixel[0] != pixel[1] || pixel[1] != pixel[2]) return false;
    }
  }
  return true;
}

}  // namespace attend
