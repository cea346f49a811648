// The "key: numbers" text files that rectified rigs give their calibration in (KITTI's
// calib_cam_to_cam.txt, calib_velo_to_cam.txt and calib/NNNN.txt, EuRoC's calib.txt), and the
// rectified form of a pair of projection matrices read from one (io/stereo_calibration.h).
#pragma once

#include <map>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "io/stereo_calibration.h"

namespace attend {

// One file of "KEY: v1 v2 ..." lines. KITTI's tracking calib/NNNN.txt writes some keys without
// the colon ("R_rect 0.9999 ..."), so a line's key is the text before a colon that ends its
// first word, else its first word. '#' starts a comment; blank lines are skipped.
class CalibrationText {
 public:
  // InputError when the file cannot be read.
  explicit CalibrationText(const std::string& path);

  bool Has(const std::string& key) const { return entries_.count(key) > 0; }
  // The `count` numbers of `key`. InputError naming the file (and the line) when the key is
  // missing, holds another count, a word that is not a number, or a value that is not finite.
  // A key whose value is not all numbers (KITTI's calib_time) is an error only when asked for.
  std::vector<double> Numbers(const std::string& key, size_t count) const;
  // `key` as a rows x cols matrix (CV_64F), row by row.
  cv::Mat Matrix(const std::string& key, int rows, int cols) const;
  // The first of `keys` the file has ("" when none): KITTI names one matrix differently in its
  // tracking and object sets (R_rect, R0_rect).
  std::string FirstOf(const std::vector<std::string>& keys) const;
  const std::string& path() const { return path_; }

 private:
  struct Entry {
    int line = 0;
    std::vector<double> numbers;
    std::string bad_word;  // the first word that is not a number; "" when all are
  };
  std::string path_;
  std::map<std::string, Entry> entries_;
};

// The rectified form of projections `left` and `right` (3x4, CV_64F) that share their
// intrinsics, both in one rectified frame (KITTI's is camera 0's): P1 = [K | 0],
// P2 = [K | right - left] in the left camera's frame, at `size`. InputError naming `source`
// for an unknown size, a focal length that is not positive or a right camera that is not to the
// right of the left one.
StereoCalibration RectifiedFromProjections(const std::string& source, const cv::Mat& left,
                                           const cv::Mat& right, cv::Size size);

}  // namespace attend
