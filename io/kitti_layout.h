// KITTI's own layouts, as users have them unpacked (SPEC 3.1, docs/SEQUENCES.md): where a raw
// drive's or a tracking sequence's frames, calibration, labels and LiDAR scans are.
//
//   raw drive   DATE/DATE_drive_NNNN_sync/image_02/data/0000000000.png, image_03/data/...,
//               velodyne_points/data/0000000000.bin, tracklet_labels.xml; the calibration in
//               the date folder: DATE/calib_cam_to_cam.txt, DATE/calib_velo_to_cam.txt
//   tracking    training/image_02/NNNN/000000.png (the folder attend run is given),
//               training/image_03/NNNN/, training/calib/NNNN.txt, training/label_02/NNNN.txt,
//               training/velodyne/NNNN/000000.bin
#pragma once

#include <optional>
#include <string>

namespace attend {

enum class KittiLayout { kRawDrive, kTracking };

// The files of one KITTI sequence. Labels and scans are optional ("" when absent): the frames
// and the calibration are what a run needs.
struct KittiSequence {
  KittiLayout layout = KittiLayout::kRawDrive;
  std::string folder;        // as given: the drive folder, or training/image_02/NNNN
  std::string name;          // the drive folder's name ("2011_09_26_drive_0005_sync"), or NNNN
  std::string left_frames;   // image_02/data, or training/image_02/NNNN
  std::string right_frames;  // image_03/data, or training/image_03/NNNN
  // Raw: the date folder (calib_cam_to_cam.txt, calib_velo_to_cam.txt); tracking:
  // calib/NNNN.txt.
  std::string calibration;
  std::string labels;  // tracklet_labels.xml or label_02/NNNN.txt, "" when absent
  std::string scans;   // velodyne_points/data or velodyne/NNNN, "" when absent

  // The LiDAR scan of the frame whose image file has the stem `stem`: SCANS/STEM.bin.
  std::string ScanPath(const std::string& stem) const;
};

// A raw drive folder: it has image_02/data and image_03/data.
bool IsKittiRawDrive(const std::string& folder);
// A tracking sequence's left frames: a folder NNNN inside image_02 whose sibling image_03/NNNN
// exists.
bool IsKittiTracking(const std::string& folder);

// The files of the KITTI sequence `folder`, nullopt when it is in neither layout (or is a
// sequence folder of attend's own, which has left/). Does not check that the calibration
// exists: opening does, naming it.
std::optional<KittiSequence> FindKittiSequence(const std::string& folder);

}  // namespace attend
