#include "eval/disparity_scores.h"

#include <cmath>
#include <limits>

namespace attend {

BadPixelRates EvaluateDisparity(const cv::Mat& disparity, const cv::Mat& ground_truth) {
  CV_Assert(disparity.type() == CV_32FC1 && ground_truth.type() == CV_32FC1 &&
            disparity.size() == ground_truth.size());
  BadPixelRates rates;
  int bad1 = 0, bad2 = 0;
  for (int y = 0; y < disparity.rows; ++y) {
    const float* d = disparity.ptr<float>(y);
    const float* g = ground_truth.ptr<float>(y);
    for (int x = 0; x < disparity.cols; ++x) {
      if (!(g[x] > 0.f) || !std::isfinite(g[x])) continue;
      ++rates.known;
      const bool valid = d[x] >= 0.f && std::isfinite(d[x]);
      const float error = valid ? std::abs(d[x] - g[x]) : std::numeric_limits<float>::infinity();
      bad1 += error > 1.f;
      bad2 += error > 2.f;
    }
  }
  if (rates.known > 0) {
    rates.bad1 = static_cast<double>(bad1) / rates.known;
    rates.bad2 = static_cast<double>(bad2) / rates.known;
  }
  return rates;
}

}  // namespace attend
