// Cell features for the correlation tracker (tracker/correlation_tracker.h): histograms of
// oriented gradients over square cells with the 31 channels of Felzenszwalb et al. (PAMI 2010,
// "Object detection with discriminatively trained part-based models", section 6.3), and the
// cell's mean intensity as a 32nd channel. Not part of the API.
//
// Per pixel, the gradient (central differences) of the colour channel with the largest
// magnitude votes its magnitude into the signed orientation bin (of 18 over 360 degrees) whose
// direction it is closest to, in the cell that holds the pixel. Each cell is normalised by the
// gradient energy of the four 2 x 2 blocks of cells it belongs to, each normalised value
// truncated at 0.2; the channels are the 18 signed and 9 unsigned orientations summed over the
// four normalisations (times 0.5), and four texture channels, the truncated energy of each
// normalisation (times 0.2357).
#pragma once

#include <opencv2/core.hpp>
#include <vector>

namespace attend {
namespace tracker_internal {

constexpr int kHogChannels = 32;  // 18 signed, 9 unsigned, 4 texture, 1 intensity

// Computes the features; keeps its buffers between calls.
class HogCells {
 public:
  // The features of `patch` (8-bit BGR), whose sides must be multiples of `cell`:
  // kHogChannels CV_32FC1 maps of (rows / cell) x (cols / cell) cells each, in `channels`
  // (whose maps are reused when they have that size).
  void Compute(const cv::Mat& patch, int cell, std::vector<cv::Mat>* channels);

 private:
  void Histograms(const cv::Mat& patch, int cell, int rows, int cols);

  std::vector<float> histogram_;  // per cell 18 signed bins
  std::vector<float> grey_;       // per cell the sum of grey levels
  std::vector<float> energy_;     // per cell, padded by one cell each side
};

}  // namespace tracker_internal
}  // namespace attend
