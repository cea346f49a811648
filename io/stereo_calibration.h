// A stereo camera's calibration (SPEC 3.1, SEQ/calib.yaml): OpenCV's stereo calibration in
// FileStorage YAML, as `attend calibrate` writes it (cv::stereoCalibrate, cv::stereoRectify),
// and what a sequence's frames need of it: the rectification of a raw pair, and the rectified
// pair's projection matrices, which turn a disparity into a position in metres.
//
// Three forms are read, in this order of preference (docs/STEREO3D.md):
//   full       K1, D1, K2, D2, R, T and image_size (with R1, R2, P1, P2, Q when the file has
//              them; stereoRectify's otherwise): the pair is raw, and is rectified on the fly;
//   rectified  P1 and P2 only (with image_size): the pair is already rectified (KITTI's P2/P3,
//              EuRoC's calib.txt converted; docs/STEREO3D.md says how);
//   nominal    sequence.yaml's focal_px and baseline_m, the principal point at the image centre.
#pragma once

#include <memory>
#include <opencv2/core.hpp>
#include <string>

namespace attend {

struct StereoCalibration {
  enum class Form { kFull, kRectified, kNominal };
  Form form = Form::kNominal;
  std::string source;   // the file read, or "SEQ/sequence.yaml (focal_px, baseline_m)"
  cv::Size image_size;  // the native frame size the calibration is for
  // kFull only: the raw cameras (CV_64F): intrinsics, distortion, and the right camera's pose
  // in the left's (x_right = R x_left + T, T in metres).
  cv::Mat K1, D1, K2, D2, R, T;
  // Every form: the rectification (R1, R2: identity unless kFull) and the rectified cameras'
  // 3x4 projections P1, P2 and the 4x4 disparity-to-depth map Q (CV_64F).
  cv::Mat R1, R2, P1, P2, Q;
  double rms_px = -1.0;  // kFull as `attend calibrate` wrote it: its RMS reprojection error

  // The rectified left camera: focal length and principal point, pixels of image_size.
  double focal_px() const { return P1.at<double>(0, 0); }
  double cx() const { return P1.at<double>(0, 2); }
  double cy() const { return P1.at<double>(1, 2); }
  // The baseline, metres (-P2(0,3) / P2(0,0)); positive when the right camera is to the right.
  double baseline_m() const { return -P2.at<double>(0, 3) / P2.at<double>(0, 0); }
  // Whether the pair must be rectified before matching (kFull).
  bool rectifies() const { return form == Form::kFull; }
};

// Reads `path` (InputError, exit status 3, naming the file and the key that is missing or
// malformed: a matrix of the wrong size, a non-positive focal length, a zero baseline).
StereoCalibration ReadStereoCalibration(const std::string& path);
// Writes `calibration` in the form ReadStereoCalibration reads (IoError when it cannot).
void WriteStereoCalibration(const StereoCalibration& calibration, const std::string& path);
// The nominal form: focal length `focal_px` and baseline `baseline_m` at `image_size`, the
// principal point at the image centre ((width - 1) / 2, (height - 1) / 2).
StereoCalibration NominalCalibration(double focal_px, double baseline_m, cv::Size image_size,
                                     const std::string& source);

// Rectifies raw pairs of a kFull calibration (cv::initUndistortRectifyMap, cv::remap with
// linear interpolation), at the calibration's image size.
class Rectifier {
 public:
  explicit Rectifier(const StereoCalibration& calibration);
  // Rectifies both views in place (InputError when their size is not the calibration's).
  void Apply(cv::Mat* left, cv::Mat* right) const;

 private:
  cv::Mat left_x_, left_y_, right_x_, right_y_;
  cv::Size size_;
};

}  // namespace attend
