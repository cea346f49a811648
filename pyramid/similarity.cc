#include "pyramid/similarity.h"

#include "colour/colour.h"
#include "util/error.h"

namespace attend {

float HsvSimilarity::Threshold(int level, int top_regular_level) const {
  if (level <= 0) return t_max_;
  if (top_regular_level <= 0 || level > top_regular_level) return 0.3f * t_max_;
  return t_max_ * (1.f - 0.7f * static_cast<float>(level) / static_cast<float>(top_regular_level));
}

void HsvSimilarity::Features(const cv::Mat& bgr, cv::Mat* features) {
  BgrToCylinder(bgr, features);
}

void ClassSimilarity::Features(const cv::Mat& class_map, cv::Mat* features) {
  ATTEND_CHECK(class_map.type() == CV_8UC1) << "class map must be CV_8UC1";
  features->create(class_map.size(), CV_32FC3);
  for (int row = 0; row < class_map.rows; ++row) {
    const uchar* in = class_map.ptr<uchar>(row);
    float* out = features->ptr<float>(row);
    for (int col = 0; col < class_map.cols; ++col) {
      out[3 * col] = in[col] != 0 ? 255.f : 0.f;
      out[3 * col + 1] = 0.f;
      out[3 * col + 2] = 0.f;
    }
  }
}

}  // namespace attend
