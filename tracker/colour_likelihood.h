// The correlation tracker's colour model (tracker/correlation_tracker.h): histograms of the
// target's colours and of its surroundings', whose ratio gives each pixel's likelihood of being
// the target, as in Bertinetto et al.'s Staple (CVPR 2016, "Staple: complementary learners for
// real-time tracking"). Not part of the API.
#pragma once

#include <opencv2/core.hpp>
#include <vector>

namespace attend {
namespace tracker_internal {

class ColourLikelihood {
 public:
  // `bins` per BGR channel.
  explicit ColourLikelihood(int bins);

  // Learns from `patch` (8-bit BGR): the target's colours from the pixels of `inner`, the
  // surroundings' from the pixels outside `target`; each histogram normalised and blended in
  // by `rate` (1: replaces it). A side without pixels keeps its histogram.
  void Learn(const cv::Mat& patch, const cv::Rect& inner, const cv::Rect& target, double rate);
  // Per pixel of `patch` (8-bit BGR) f / (f + b) of its colour's bin (CV_32F, 0..1; 0 where
  // neither histogram has the colour).
  void Likelihood(const cv::Mat& patch, cv::Mat* likelihood) const;
  bool trained() const { return trained_; }

 private:
  int Bin(const cv::Vec3b& pixel) const {
    return ((pixel[0] >> shift_) * bins_ + (pixel[1] >> shift_)) * bins_ + (pixel[2] >> shift_);
  }

  int bins_;
  int shift_;  // bins_ is rounded to a power of two: a bin holds 2^shift_ levels
  std::vector<float> target_, surroundings_;
  std::vector<float> in_, out_;  // counts, kept between calls
  bool trained_ = false;
};

// The colour model's response on the window's grid of cells (`cells`, `cell` pixels a side):
// at index (i, j) the mean of `likelihood` (CV_32F, the window's pixels) over a box of
// `target` pixels centred at pixel (i x cell, j x cell), so that index (cols / 2, rows / 2) is
// the window's centre, as for the translation filter's response (outside the window counts 0).
cv::Mat ColourResponse(const cv::Mat& likelihood, cv::Size cells, int cell, cv::Size target);

}  // namespace tracker_internal
}  // namespace attend
