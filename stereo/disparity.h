// Dense disparity by zero-mean normalised cross-correlation and Sun's two-stage dynamic
// programming (thesis 5.1.1 "Disparity"; SPEC 2.3; C. Sun, "Fast stereo matching using
// rectangular subregioning and 3D maximum-surface techniques", IJCV 47, 2002).
//
// For every disparity d in 0..D-1 the ZNCC of the window around (x, y) in the left image and
// around (x - d, y) in the right image is computed with box filters, so its cost per voxel does
// not depend on the window. The disparity map is the maximum surface of that M x N x D volume
// under |d(x) - d(x-1)| <= 1 along rows:
//   stage 1, every row: Y(x, d) = C(x, d) + max_{t in -1..1} Y(x - 1, d + t), with the argmax
//            kept in 2 bits a voxel;
//   stage 2: the same recursion along y over the rows' last columns Y(M - 1, y, d), which picks
//            for each row an end disparity consistent with its neighbours;
//   then every row is backtracked from its end disparity.
// Rectified pairs are assumed: a left pixel (x, y) matches the right pixel (x - d, y).
#pragma once

#include <memory>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "util/option_fields.h"

namespace attend {

// Stage 1's smoothness along rows (DisparityOptions::smoothness).
enum class DisparitySmoothness { kHard, kPenalty, kSgm };
// "hard", "penalty", "sgm".
const char* DisparitySmoothnessName(DisparitySmoothness smoothness);

struct DisparityOptions {
  // The largest D: the cost volume's back-pointers take width x height x D / 4 bytes
  // (640 x 480 x 1024 / 4 = 79 MB).
  static constexpr int kMaxDisparity = 1024;
  // D: disparities 0..D-1 are searched. Must be below the image width.
  int max_disparity = 32;
  // Side of the square ZNCC window, odd. 5 is the best of 3, 5, 7 for sgm on Middlebury; 7
  // was the best of 5..13 for the hard smoothness on the synthetic scenes and on Middlebury
  // (docs/DISPARITY.md); the thesis does not give one.
  int window = 5;
  // Parabola through the correlation peak and its two neighbours: disparities in fractions of a
  // pixel (within half a pixel of the integer one).
  bool subpixel = false;
  // Left-right consistency: the right image's disparity map is computed too, winner-take-all
  // from the same correlations (C_R(xr, d) = C(xr + d, d), the best d; as OpenCV's SGBM does
  // for its check), and a left pixel whose match disagrees by more than `lr_tolerance` pixels
  // is invalid; invalid pixels are then filled from the nearest valid pixel on their row,
  // taking the farther (smaller) disparity of the two sides, as occlusions are background.
  // On by default: it lowers the Middlebury bad-pixel rate below StereoBM's (filled), and
  // costs about a sixth of the time (docs/DISPARITY.md). The thesis has no such check.
  bool left_right_check = true;
  int lr_tolerance = 1;
  // Stage 1's smoothness along rows: hard, the thesis's |d(x) - d(x-1)| <= 1, which forces a
  // ramp of k columns at every depth edge of k pixels; or penalty, which also lets d jump
  // from the previous column's best disparity at the cost `jump_penalty` (in ZNCC units, which
  // are in [-1, 1] per pixel) and so keeps depth edges sharp (a departure, docs/DISPARITY.md).
  // Or sgm: the correlations, as costs 1 - ZNCC, aggregated along eight paths through each
  // pixel (semi-global matching, Hirschmüller 2008; stereo/semi_global.h) with penalties
  // `sgm_p1` for a step of one disparity and `sgm_p2` for a larger jump (ZNCC units), and the
  // disparity of the least sum.
  // The default, sgm, has a lower bad-pixel rate than OpenCV's StereoSGBM on all ten Middlebury
  // pairs of the reference data at about its time (docs/DISPARITY.md); the penalties were
  // chosen on those pairs. The thesis's method: `smoothness: hard, window: 9,
  // left_right_check: false, median: 0`; the defaults before sgm: `hard`, window 7, median 0.
  DisparitySmoothness smoothness = DisparitySmoothness::kSgm;
  float jump_penalty = 1.0f;
  float sgm_p1 = 0.6f;
  float sgm_p2 = 2.5f;
  // sgm: 8 paths (two passes over the volume, kept: 3 bytes a voxel) or 5 (the four from above
  // and the left and the one from the right, one pass a row as the costs arrive, no volume; as
  // OpenCV's StereoSGBM in its default mode).
  int sgm_paths = 5;
  // A median filter of this size (3 or 5; 0: none) over the map, after the left-right check:
  // it removes the small blobs of wrong disparity that a window cost leaves on fine texture.
  int median = 5;
  // The widest image the estimator works on: a wider pair is halved (area averaging) until it
  // is at most this wide, D with it (rounded up), and the map is scaled back to the pair's size
  // (nearest neighbour, disparities times the factor), so its values step by the factor. The
  // time then stays near that of a pair of this width: 640x480 with D = 64 and max_width 320
  // costs about an eighth. 0: always full size (the thesis's computation). The attention
  // loop's configuration sets 320 (configs/default.yaml; docs/DISPARITY.md measures the loss).
  int max_width = 0;

  // "" when valid; otherwise names the field and the broken constraint.
  std::string Check() const;
  // The fields (util/option_fields.h): the keys of the disparity feature and of --set.
  static const OptionFields<DisparityOptions>& Fields();

  bool operator==(const DisparityOptions&) const = default;
};

// Computes disparity maps; keeps its buffers between calls, so a stream of frames of one size
// allocates nothing after the first.
class DisparityEstimator {
 public:
  explicit DisparityEstimator(DisparityOptions options = {});
  ~DisparityEstimator();
  DisparityEstimator(const DisparityEstimator&) = delete;
  DisparityEstimator& operator=(const DisparityEstimator&) = delete;

  // `left` and `right`: 8-bit images of one size, grey or BGR (converted to grey). The result
  // is CV_32FC1 in pixels, >= 0 everywhere (the method is dense). InputError when the sizes
  // differ or D is not below the width.
  void Compute(const cv::Mat& left, const cv::Mat& right, cv::Mat* disparity);

  // Where the last Compute measured a disparity (CV_8UC1, the pair's size, 255 where it did):
  // the pixels that passed the left-right check (every pixel without the check), whose
  // matching window has texture, a grey standard deviation of at least kMeasuredMinTexture,
  // and that lie right of the first D - 1 columns (which the right view does not show at every
  // disparity searched).
  // The map itself is dense: it fills the others (the sky, a blank wall, occlusions) with a
  // guess, which carries no depth evidence (docs/DISPARITY.md, "Measured pixels").
  const cv::Mat& measured() const { return measured_; }
  static constexpr double kMeasuredMinTexture = 2.0;

  // Milliseconds of the last Compute (conversion to grey included).
  double milliseconds() const { return milliseconds_; }
  const DisparityOptions& options() const { return options_; }

  // Bytes held in buffers after the last Compute (the cost volume, back-pointers and the rest).
  size_t buffer_bytes() const;

 private:
  struct Buffers;
  void Estimate(const cv::Mat& left, const cv::Mat& right, int depth, cv::Mat* disparity);
  void EstimateSemiGlobal(const cv::Mat& left, const cv::Mat& right, int depth,
                          cv::Mat* disparity);

  // measured_ from the map before filling (`map`, negative where the check failed) and the
  // grey left image it was computed from.
  void MarkMeasured(const cv::Mat& map, const cv::Mat& left_grey, int depth, cv::Size size);

  DisparityOptions options_;
  cv::Mat measured_;
  // Owned through unique_ptr so that it is freed when the constructor throws on bad options.
  std::unique_ptr<Buffers> buffers_;
  double milliseconds_ = 0.0;
};

}  // namespace attend
