// How the pyramid decides that two vertices are similar (thesis 3.2, 5.1.2).
//
// Every vertex carries a feature vector of three floats, the area-weighted mean of its sons'
// (at level 0, the pixel's). Two vertices of level l are similar when the Euclidean distance
// between their vectors is below the policy's threshold T(l). A policy is the pair (how level-0
// features are made, T(l)); the pyramid itself has one code path for all of them, so the inner
// loops pay no virtual call per comparison.
#pragma once

#include <opencv2/core.hpp>

namespace attend {

class SimilarityPolicy {
 public:
  virtual ~SimilarityPolicy() = default;
  // T(l) for linking vertices of level l (building level l + 1). `top_regular_level` is
  // L_reg = floor(log2(min(width, height))).
  virtual float Threshold(int level, int top_regular_level) const = 0;
};

// The HSV cylinder distance with the thesis schedule (eq. 3.1, 3.2):
// T(l) = T_max * a(l), a(l) = 1 - 0.7 l / L_reg for l <= L_reg, 0.3 above.
class HsvSimilarity final : public SimilarityPolicy {
 public:
  explicit HsvSimilarity(float t_max) : t_max_(t_max) {}
  float Threshold(int level, int top_regular_level) const override;
  float t_max() const { return t_max_; }
  // Level-0 features: the HSV cylinder image (colour/colour.h) of an 8-bit BGR image.
  static void Features(const cv::Mat& bgr, cv::Mat* features);

 private:
  float t_max_;
};

// "Same class": vertices are similar iff they belong to the same class of a binary map, such
// as skin / not skin (thesis 5.1.2). Features are (255 * class, 0, 0) and the threshold is
// fixed between 0 and 255, so only vertices of one class ever link and every mean stays
// exactly 0 or 255.
class ClassSimilarity final : public SimilarityPolicy {
 public:
  float Threshold(int, int) const override { return 127.5f; }
  // Level-0 features of a CV_8UC1 class map (non-zero = class 1).
  static void Features(const cv::Mat& class_map, cv::Mat* features);
};

}  // namespace attend
