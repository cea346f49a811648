// Semi-global aggregation of a matching-cost volume (H. Hirschmüller, "Stereo processing by
// semiglobal matching and mutual information", PAMI 30(2), 2008): the estimator's
// `smoothness: sgm` (stereo/disparity.h), which replaces the thesis's one scanline a row by
// eight paths through each pixel. Internal to stereo/.
//
// Along each path r the cost of disparity d at pixel p is
//   L_r(p, d) = C(p, d) + min(L_r(p - r, d), L_r(p - r, d +- 1) + P1, min_k L_r(p - r, k) + P2)
//               - min_k L_r(p - r, k),
// and the disparity of p is the d of the least sum S(p, d) over the eight paths (left, right,
// up, down and the four diagonals). Costs are bytes (0..254); L_r stays below 255 + P2, so
// the sum of eight fits in 16 bits.
//
// Eight paths take two passes: the first goes down the image (left to right) along the four
// paths that come from above and the left and stores their sum; the second goes up (right to
// left) along the other four and, as each pixel's sum is complete, takes its disparity (and
// the right view's candidates) at once. Five paths (the four from above and the left, and
// right to left along the row, as OpenCV's StereoSGBM in its default mode) take one pass, a
// row at a time as its costs arrive, and keep no volume.
#pragma once

#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

namespace attend {

class SemiGlobalAggregator {
 public:
  // The largest cost a voxel may have.
  static constexpr int kMaxCost = 254;
  // The largest penalty.
  static constexpr int kMaxPenalty = 2047;
  // Disparities are handled in groups of this many (one AVX2 vector of 16-bit lanes).
  static constexpr int kLanes = 16;

  struct Setup {
    int width = 0, height = 0, depth = 0;
    int paths = 8;          // 8 or 5
    int p1 = 0, p2 = 0;     // penalties, p1 <= p2 <= kMaxPenalty
    bool subpixel = false;  // a parabola through the sums at d - 1, d, d + 1
  };

  // Starts a pair. `left` receives the left view's disparities (per pixel the d of the least
  // sum, the smaller on a tie) and, when not null, `right` the right view's, winner-take-all
  // along the diagonal S(xr + d, d) (the smaller d on a tie; as OpenCV's SGBM does for its
  // left-right check); both CV_32FC1, complete after Finish().
  void Begin(const Setup& setup, cv::Mat* left, cv::Mat* right);

  // Costs per pixel: `depth` rounded up to kLanes.
  int stride() const { return stride_; }

  // The costs of row y, [x][stride()], to fill with costs in 0..kMaxCost for d < depth (the
  // rest are set by Begin()); rows in order 0, 1, ..., each followed by EndRow(y).
  uint8_t* cost_row(int y);
  void EndRow(int y);

  // After the last row.
  void Finish();

  size_t bytes() const {
    return cost_.capacity() +
           (sum_.capacity() + paths_.capacity() + minima_.capacity() + right_best_.capacity() +
            right_best_d_.capacity()) *
               sizeof(int16_t);
  }

 private:
  // Writes row y of the right view from its candidates (after the row's pass).
  void TakeRightRow(int y);

  Setup setup_;
  int stride_ = 0;
  size_t slot_ = 0;  // one path's costs of one pixel, padded
  cv::Mat* left_ = nullptr;
  cv::Mat* right_ = nullptr;
  // Eight paths: [y][x][stride]; five: one row. Costs of d >= depth are 255.
  std::vector<uint8_t> cost_;
  // Eight paths: the first pass's sums, [y][x][stride]; five: one row's.
  std::vector<int16_t> sum_;
  // L_r of the previous and current row for the three paths that come from the row before,
  // and of the previous pixel for the path along the row, each [stride] with kLanes values of
  // padding before and after, so that d - 1 and d + 1 need no test; then one pixel's whole
  // sum; then the costs of no predecessor.
  std::vector<int16_t> paths_;
  std::vector<int16_t> minima_;  // min_k L_r of each of those, per pixel
  std::vector<int16_t> right_best_;  // the right view's best sums of a row, and their d
  std::vector<int16_t> right_best_d_;
};

}  // namespace attend
