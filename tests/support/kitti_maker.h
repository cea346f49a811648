// Small sequences in KITTI's own layouts (io/kitti_layout.h) for tests: a rig whose numbers a
// test can project by hand, its calibration files, a tracklet of one car, a scan of a flat
// ground, and the frames.
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "tests/support/temp_dir.h"

namespace attend::testing {

// A level rig: R_rect identity, the Velodyne at the camera's place (T = 0) with the axes turned
// (camera x = -velo y, y = -velo z, z = velo x), the left camera 0.06 m left of camera 0 (as
// KITTI's camera 2 is), the right one `baseline` to its right.
struct KittiTestRig {
  double focal = 100.0, cx = 100.0, cy = 50.0, baseline = 0.54;
  cv::Size size{200, 100};

  std::string CamToCam() const;   // calib_cam_to_cam.txt
  std::string VeloToCam() const;  // calib_velo_to_cam.txt
  std::string Tracking() const;   // calib/NNNN.txt of the tracking set (R_rect, Tr_velo_cam)
};

// One car, l 4 w 2 h 1.5, at Velodyne (10, 0, -1.73) from frame 0 for `frames` frames.
std::string OneCarTracklet(int frames);

// A flat ground at Velodyne z = -1.73 (x 4..20, y -4..4, every metre: 153 points), 9 points on a
// car's rear at x = 8 (0.53 m and more above the ground), and 2 behind the Velodyne.
std::vector<cv::Vec4f> FlatGroundScan();
void WriteScan(const std::string& path, const std::vector<cv::Vec4f>& scan);

// A raw drive DIR/2011_09_26/2011_09_26_drive_0001_sync of `left.size()` frames, with its
// calibration, the car's tracklets and a flat-ground scan per frame; returns the drive folder.
std::string WriteKittiRawDrive(const TempDir& dir, const KittiTestRig& rig,
                               const std::vector<cv::Mat>& left, const std::vector<cv::Mat>& right);
// A tracking sequence DIR/training/image_02/0000 ... with calib/0000.txt, a label of the car in
// every frame and a DontCare, and the scans; returns the image_02/0000 folder.
std::string WriteKittiTracking(const TempDir& dir, const KittiTestRig& rig,
                               const std::vector<cv::Mat>& left, const std::vector<cv::Mat>& right);

// The car's box in the left image of the default rig, worked out by hand: its 8 corners at
// camera (X, Y, Z) = (0.06 - y, -z, x) for x in {8, 12}, y in {-1, 1}, z in {-1.73, -0.23}
// give u = 100 X / Z + 100 in [88.25, 113.25] and v = 100 Y / Z + 50 in [51.9167, 71.625].
inline cv::Rect2d CarBox() {
  return {88.25, 50.0 + 23.0 / 12.0, 25.0, 71.625 - 50.0 - 23.0 / 12.0};
}

}  // namespace attend::testing
