// KITTI's per-frame files besides the images (the devkit readmes): a tracking sequence's labels,
// label_02/NNNN.txt, and the Velodyne scans of every layout (raw velodyne_points/data/*.bin,
// tracking velodyne/NNNN/*.bin, object velodyne/*.bin).
#pragma once

#include <limits>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace attend {

// One line of label_02/NNNN.txt (tracking devkit readme): 17 values, or 18 with a score.
struct KittiLabel {
  int frame = 0;
  int track_id = -1;       // -1 for DontCare
  std::string type;        // Car, Van, Truck, Pedestrian, Person_sitting, Cyclist, Tram, Misc,
                           // DontCare
  double truncated = 0.0;  // 0 (in the image) .. 1 (leaving it)
  int occluded = 0;        // 0 fully visible, 1 partly, 2 largely occluded, 3 unknown
  double alpha = 0.0;      // observation angle, radians
  cv::Rect2d box;          // left, top, right, bottom in the left image, as a box
  double h = 0.0, w = 0.0, l = 0.0;  // dimensions, metres
  cv::Vec3d location;  // the box's bottom centre in camera 0's rectified frame, metres
  double rotation_y = 0.0;
  double score = std::numeric_limits<double>::quiet_NaN();  // results only
};

// Reads label_02/NNNN.txt. InputError naming the file and line of a line with another count of
// values, a value that is not a number, or a box whose right or bottom is before its left or top.
std::vector<KittiLabel> ReadKittiTrackingLabels(const std::string& path);

// One Velodyne scan: float32 x, y, z, reflectance per point (metres in the Velodyne's frame: x
// forward, y left, z up). InputError when the file cannot be read or its size is not a
// multiple of 16 bytes.
std::vector<cv::Vec4f> ReadVelodyneScan(const std::string& path);

}  // namespace attend
