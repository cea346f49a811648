#include "eval/kitti_truth.h"

#include <algorithm>
#include <filesystem>

#include "io/frame_files.h"
#include "util/error.h"

namespace attend {

namespace fs = std::filesystem;

namespace {

// The 8 corners of a tracklet box in the Velodyne's frame (devkit: x along the length, y along
// the width, z up from the box's bottom, rotated by rz about z and moved to (tx, ty, tz)).
std::vector<cv::Vec3d> BoxCorners(const KittiTracklet& t, const KittiTrackletPose& pose) {
  const double c = std::cos(pose.rz), s = std::sin(pose.rz);
  std::vector<cv::Vec3d> corners;
  for (int i = 0; i < 8; ++i) {
    const double x = ((i & 1) ? 0.5 : -0.5) * t.l;
    const double y = ((i & 2) ? 0.5 : -0.5) * t.w;
    const double z = (i & 4) ? t.h : 0.0;
    corners.emplace_back(pose.tx + c * x - s * y, pose.ty + s * x + c * y, pose.tz + z);
  }
  return corners;
}

// The depth of an object at `depth_m` as a disparity of the rig, or none.
std::optional<double> DisparityAt(const KittiRig& rig, double depth_m) {
  if (!(depth_m > 0)) return std::nullopt;
  return rig.stereo.focal_px() * rig.stereo.baseline_m() / depth_m;
}

// The left frames' stems in frame order, and their size.
std::vector<std::string> FrameStems(const KittiSequence& sequence, cv::Size* size) {
  const std::vector<std::string> files = ListFrameFiles(sequence.left_frames, sequence.folder);
  if (files.empty()) throw InputError(sequence.left_frames + ": no frames");
  *size = ReadFrameFile(0, files[0]).size();
  std::vector<std::string> stems;
  for (const std::string& file : files) stems.push_back(fs::path(file).stem().string());
  return stems;
}

// The tracking labels of frame `frame` (DontCare left out) as truth objects.
std::vector<TruthObject> LabelObjects(const std::vector<KittiLabel>& labels, const KittiRig& rig,
                                      int frame) {
  std::vector<TruthObject> objects;
  for (const KittiLabel& label : labels) {
    if (label.frame != frame || label.type == "DontCare") continue;
    TruthObject object;
    object.id = label.track_id;
    object.box = label.box;
    object.kind = label.type;
    // The labels' locations are in camera 0's rectified frame; the left camera sits beside it.
    object.depth_m = rig.LeftCameraFromRect(label.location)[2];
    objects.push_back(object);
  }
  return objects;
}

}  // namespace

double KittiVisibleFraction(int occlusion) {
  switch (occlusion) {
    case 1:
      return 0.5;
    case 2:
      return 0.2;
    default:
      return 1.0;
  }
}

std::vector<TruthObject> TrackletObjects(const std::vector<KittiTracklet>& tracklets,
                                         const KittiRig& rig, cv::Size size, int frame) {
  std::vector<TruthObject> objects;
  const cv::Rect2d image(0, 0, size.width, size.height);
  for (size_t id = 0; id < tracklets.size(); ++id) {
    const KittiTracklet& t = tracklets[id];
    const int index = frame - t.first_frame;
    if (index < 0 || index >= static_cast<int>(t.poses.size())) continue;
    const KittiTrackletPose& pose = t.poses[index];
    double left = 1e300, top = 1e300, right = -1e300, bottom = -1e300;
    bool in_front = true;
    for (const cv::Vec3d& corner : BoxCorners(t, pose)) {
      const cv::Vec3d x = rig.LeftCameraFromVelo(corner);
      if (x[2] < kMinCornerDepthM) in_front = false;
      if (!in_front) break;
      const cv::Point2d p = rig.Project(x);
      left = std::min(left, p.x);
      right = std::max(right, p.x);
      top = std::min(top, p.y);
      bottom = std::max(bottom, p.y);
    }
    if (!in_front) continue;
    const cv::Rect2d box = cv::Rect2d(left, top, right - left, bottom - top) & image;
    if (box.width <= 0 || box.height <= 0) continue;
    TruthObject object;
    object.id = static_cast<int>(id);
    object.box = box;
    object.kind = t.type;
    object.depth_m = rig.LeftCameraFromVelo(cv::Vec3d(pose.tx, pose.ty, pose.tz + 0.5 * t.h))[2];
    objects.push_back(object);
  }
  return objects;
}

KittiRig ReadKittiRig(const KittiSequence& sequence, cv::Size size) {
  return sequence.layout == KittiLayout::kRawDrive
             ? ReadKittiRawCalibration(sequence.calibration, size)
             : ReadKittiFrameCalibration(sequence.calibration, size);
}

SceneTruth ReadKittiTruth(const KittiSequence& sequence) {
  cv::Size size;
  const std::vector<std::string> stems = FrameStems(sequence, &size);
  const KittiRig rig = ReadKittiRig(sequence, size);
  std::vector<KittiTracklet> tracklets;
  std::vector<KittiLabel> labels;
  if (!sequence.labels.empty() && sequence.layout == KittiLayout::kRawDrive) {
    tracklets = ReadKittiTracklets(sequence.labels);
  } else if (!sequence.labels.empty()) {
    labels = ReadKittiTrackingLabels(sequence.labels);
  }
  SceneTruth truth;
  for (int frame = 0; frame < static_cast<int>(stems.size()); ++frame) {
    FrameTruth& f = truth[frame];
    f.frame = frame;
    f.image_size = size;
    f.objects = sequence.layout == KittiLayout::kRawDrive
                    ? TrackletObjects(tracklets, rig, size, frame)
                    : LabelObjects(labels, rig, frame);
    if (sequence.scans.empty()) continue;
    const std::string scan = sequence.ScanPath(stems[frame]);
    std::error_code error;
    if (!fs::is_regular_file(scan, error)) continue;
    LidarTruth lidar = ProjectScan(ReadVelodyneScan(scan), rig, size);
    f.points = std::move(lidar.points);
    f.horizon = lidar.horizon;
  }
  return truth;
}

std::vector<GtObject> ReadKittiObjects(const KittiSequence& sequence) {
  if (sequence.labels.empty()) {
    throw InputError(sequence.folder + ": no labels (expected " +
                     (sequence.layout == KittiLayout::kRawDrive
                          ? std::string("tracklet_labels.xml in the drive folder")
                          : std::string("label_02/" + sequence.name + ".txt")) +
                     ")");
  }
  cv::Size size;
  // The drive's frames bound the labels' (a tracklet may say it runs beyond them).
  const int frames = static_cast<int>(FrameStems(sequence, &size).size());
  const KittiRig rig = ReadKittiRig(sequence, size);
  std::vector<GtObject> objects;
  auto add = [&](int frame, const TruthObject& object, int occlusion) {
    GtObject gt;
    gt.frame = frame;
    gt.id = object.id;
    gt.box = object.box;
    gt.visible_fraction = KittiVisibleFraction(occlusion);
    gt.disparity = DisparityAt(rig, object.depth_m);
    gt.kind = object.kind;
    objects.push_back(gt);
  };
  if (sequence.layout == KittiLayout::kTracking) {
    for (const KittiLabel& label : ReadKittiTrackingLabels(sequence.labels)) {
      for (const TruthObject& object : LabelObjects({label}, rig, label.frame)) {
        add(label.frame, object, label.occluded);
      }
    }
    return objects;
  }
  const std::vector<KittiTracklet> tracklets = ReadKittiTracklets(sequence.labels);
  for (int frame = 0; frame < frames; ++frame) {
    for (const TruthObject& object : TrackletObjects(tracklets, rig, size, frame)) {
      const KittiTracklet& t = tracklets[static_cast<size_t>(object.id)];
      add(frame, object, t.poses[static_cast<size_t>(frame - t.first_frame)].occlusion);
    }
  }
  return objects;
}

LidarTruth ReadKittiObjectFrame(const std::string& calibration, const std::string& scan,
                                cv::Size size) {
  const KittiRig rig = ReadKittiFrameCalibration(calibration, size);
  return ProjectScan(ReadVelodyneScan(scan), rig, size);
}

}  // namespace attend
