#include "eval/saliency_baselines.h"

#include <algorithm>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "eval/fixation_metrics.h"
#include "util/opencv_extra.h"

namespace attend {

namespace {

cv::Mat MinMax(const cv::Mat& map) {
  cv::Mat out;
  map.convertTo(out, CV_32F);
  double low = 0.0, high = 0.0;
  cv::minMaxLoc(out, &low, &high);
  if (high > low) {
    out = (out - low) / (high - low);
  } else {
    out.setTo(0.f);
  }
  return out;
}

cv::Mat OpenCvStatic(cvextra::StaticSaliencyType type, const cv::Mat& bgr) {
  cv::Mat map;
  if (!cvextra::Get("OpenCV's static saliency baselines").ComputeStaticSaliency(type, bgr, &map) ||
      map.empty()) {
    return cv::Mat::zeros(bgr.size(), CV_32FC1);
  }
  if (map.size() != bgr.size()) cv::resize(map, map, bgr.size(), 0, 0, cv::INTER_LINEAR);
  return MinMax(map);
}

}  // namespace

const std::vector<std::string>& BaselineNames() {
  static const std::vector<std::string> names = {"centre", "spectral_residual", "fine_grained"};
  return names;
}

cv::Mat BaselineMap(const std::string& name, const cv::Mat& bgr, double blur) {
  CV_Assert(bgr.type() == CV_8UC3 && !bgr.empty());
  cv::Mat map;
  if (name == "centre") {
    CentreBias(bgr.size()).convertTo(map, CV_32F);
    return map;
  }
  if (name == "spectral_residual") {
    map = OpenCvStatic(cvextra::StaticSaliencyType::kSpectralResidual, bgr);
  } else if (name == "fine_grained") {
    map = OpenCvStatic(cvextra::StaticSaliencyType::kFineGrained, bgr);
  } else {
    throw std::invalid_argument("unknown saliency baseline '" + name + "'");
  }
  if (blur > 0.0) {
    const double sigma = blur * std::max(bgr.cols, bgr.rows);
    cv::GaussianBlur(map, map, cv::Size(), sigma, sigma, cv::BORDER_REPLICATE);
    map = MinMax(map);
  }
  return map;
}

}  // namespace attend
