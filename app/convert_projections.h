// `attend calibrate --from-kitti FILE` and `--from-euroc FILE` (docs/STEREO3D.md): the
// projection matrices of an already rectified pair, as KITTI and EuRoC give them, turned into
// calib.yaml's rectified form (P1 the left camera's with a zero fourth column, P2 the right's
// in the left camera's frame).
#pragma once

#include <opencv2/core.hpp>
#include <string>

#include "io/stereo_calibration.h"

namespace attend {

// The rectified form from the projection matrices of a KITTI calibration: calib_cam_to_cam.txt
// (P_rect_02, P_rect_03 and the size S_rect_02) or the odometry set's calib.txt (P2, P3; its
// size from `size`, which overrides S_rect_02 when given). InputError naming the file and key.
StereoCalibration ReadKittiProjections(const std::string& path, cv::Size size);
// The rectified form from EuRoC's calib.txt as in the shared data (P_left, P_right, width,
// height). InputError naming the file and key.
StereoCalibration ReadEurocProjections(const std::string& path);

}  // namespace attend
