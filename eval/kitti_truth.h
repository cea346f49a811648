// The ground truth of a KITTI sequence (io/kitti_layout.h): its labelled objects as attend
// eval's objects (io/ground_truth.h), and its objects, LiDAR points, ground and horizon as the
// scene truth of where attention lands (eval/scene_truth.h).
//
//   raw drive   tracklet_labels.xml: each box's 8 corners through Tr_velo_to_cam, R_rect_00 and
//               P_rect_02 into the left image, the hull clipped to it; a box with a corner
//               less than kMinCornerDepthM ahead of the camera (beside or behind it) or
//               nothing left in the image is out of view. Depth: the box centre's Z.
//   tracking    label_02/NNNN.txt: the 2D boxes as given, every type but DontCare; depth: the
//               location's Z (the box's bottom centre, as deep as its centre).
//   scans       velodyne_points/data/*.bin, velodyne/NNNN/*.bin (eval/lidar_ground.h).
//
// Visible fraction from the occlusion flags (both layouts use 0 fully visible, 1 partly, 2
// largely occluded): 1, 0.5, 0.2; unknown (3, -1) counts as visible. Largely occluded objects
// therefore fall below attend eval's min_visible (0.25) and are not owed attention.
#pragma once

#include <string>
#include <vector>

#include "eval/lidar_ground.h"
#include "eval/scene_truth.h"
#include "io/ground_truth.h"
#include "io/kitti_calibration.h"
#include "io/kitti_labels.h"
#include "io/kitti_layout.h"
#include "io/kitti_tracklets.h"

namespace attend {

inline constexpr double kMinCornerDepthM = 0.1;

// The visible fraction of an occlusion flag (above).
double KittiVisibleFraction(int occlusion);

// The tracklets in view in frame `frame`, in the left image of `size`.
std::vector<TruthObject> TrackletObjects(const std::vector<KittiTracklet>& tracklets,
                                         const KittiRig& rig, cv::Size size, int frame);

// The sequence's rig for frames of `size` (its calibration files).
KittiRig ReadKittiRig(const KittiSequence& sequence, cv::Size size);

// Every frame's truth: its objects (when the sequence has labels) and its LiDAR points,
// ground and horizon (when it has scans; a frame without a scan file has none). InputError
// naming the file (and line) of a malformed label, scan or calibration.
SceneTruth ReadKittiTruth(const KittiSequence& sequence);

// The labelled objects as attend eval's ground truth, one per object and frame in view:
// id the track id (raw: the tracklet's index), kind its type, disparity focal * baseline / depth.
// InputError when the sequence has no labels, naming the file expected.
std::vector<GtObject> ReadKittiObjects(const KittiSequence& sequence);

// One frame of KITTI's object layout (calib/NNNNNN.txt, velodyne/NNNNNN.bin, image_2 of
// `size`): its LiDAR truth.
LidarTruth ReadKittiObjectFrame(const std::string& calibration, const std::string& scan,
                                cv::Size size);

}  // namespace attend
