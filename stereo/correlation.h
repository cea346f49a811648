// The disparity estimator's correlation (stereo/disparity.h): the ZNCC volume, one row at a
// time. Window sums of L(x) R(x - d) are kept per column for all d and slid down the image (add
// the entering row, subtract the leaving one), then slid along the row; every sum is of
// integers below 2^24 for windows up to 15, so float holds it exactly and the result equals
// box filtering the product image. Borders are replicated. Not part of the API that plugins
// see.
#pragma once

#include <opencv2/core.hpp>
#include <vector>

namespace attend {

// What CostRows computes before the rows: kept by the estimator between pairs, so that a
// stream of frames of one size allocates (and faults in) its pages once.
struct CostRowsStorage {
  cv::Mat left, right, left_mean, left_sigma, right_mean, right_sigma, scratch;
  std::vector<float> reversed_right;
  std::vector<float> column_sums;
  std::vector<float> window_sum;
  std::vector<float> right_mean_row, right_inverse_sigma_row;

  size_t bytes() const;
};

class CostRows {
 public:
  // `left` and `right`: CV_8UC1 of one size. `storage` holds the buffers (the estimator's, or
  // a local one); it must outlive the rows.
  CostRows(const cv::Mat& left, const cv::Mat& right, int depth, int window,
           CostRowsStorage* storage);

  // Calls `consume(y, costs)` for y = 0, 1, ...; costs[x * depth + d] is the ZNCC of (x, y) at
  // disparity d, -1 where x - d < 0. A template, so that the consumer's loops are compiled
  // into its caller.
  template <typename Consumer>
  void ForEachRow(std::vector<float>* costs, Consumer consume) {
    Start(costs);
    for (int y = 0; y < height_; ++y) {
      Row(y, costs->data());
      consume(y, static_cast<const float*>(costs->data()));
    }
  }

 private:
  // Sizes `costs` and sums the first window's column sums.
  void Start(std::vector<float>* costs);
  // Row y of the volume into `costs`, the column sums slid down to it first (y > 0).
  void Row(int y, float* costs);
  float* ReversedRight(int y) {
    return reversed_right_.data() + static_cast<size_t>(y) * (width_ + depth_);
  }
  // Adds row `in` to the column sums and, when `out` >= 0, removes row `out`.
  void SlideDown(int in, int out);

  int width_, height_, depth_, half_;
  float inverse_count_ = 1.f;
  cv::Mat &left_, &right_, &left_mean_, &left_sigma_, &right_mean_, &right_sigma_;
  std::vector<float>& reversed_right_;
  std::vector<float>& column_sums_;
  std::vector<float>& window_sum_;
  std::vector<float>& right_mean_row_;
  std::vector<float>& right_inverse_sigma_row_;
};

}  // namespace attend
