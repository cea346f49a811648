#include "io/kitti_layout.h"

#include <filesystem>

namespace attend {

namespace fs = std::filesystem;

namespace {

// `folder` without a trailing separator, absolute, so that its parents are its real ones.
fs::path Normal(const std::string& folder) {
  fs::path path = fs::absolute(fs::path(folder)).lexically_normal();
  if (path.filename().empty()) path = path.parent_path();
  return path;
}

bool IsFolder(const fs::path& path) {
  std::error_code error;
  return fs::is_directory(path, error);
}

bool IsFile(const fs::path& path) {
  std::error_code error;
  return fs::is_regular_file(path, error);
}

// `path` as a string when it exists as `file` (a file) or a folder, else "".
std::string IfPresent(const fs::path& path, bool file) {
  return (file ? IsFile(path) : IsFolder(path)) ? path.string() : "";
}

}  // namespace

std::string KittiSequence::ScanPath(const std::string& stem) const {
  return (fs::path(scans) / (stem + ".bin")).string();
}

bool IsKittiRawDrive(const std::string& folder) {
  const fs::path path = Normal(folder);
  return IsFolder(path / "image_02" / "data") && IsFolder(path / "image_03" / "data");
}

bool IsKittiTracking(const std::string& folder) {
  const fs::path path = Normal(folder);
  if (!IsFolder(path) || path.parent_path().filename() != "image_02") return false;
  return IsFolder(path.parent_path().parent_path() / "image_03" / path.filename());
}

std::optional<KittiSequence> FindKittiSequence(const std::string& folder) {
  const fs::path path = Normal(folder);
  // attend's own layout wins: a folder with left/ is a sequence folder, whatever else it holds.
  if (IsFolder(path / "left")) return std::nullopt;
  KittiSequence sequence;
  sequence.folder = folder;
  sequence.name = path.filename().string();
  if (IsKittiRawDrive(folder)) {
    sequence.layout = KittiLayout::kRawDrive;
    sequence.left_frames = (path / "image_02" / "data").string();
    sequence.right_frames = (path / "image_03" / "data").string();
    sequence.calibration = path.parent_path().string();
    sequence.labels = IfPresent(path / "tracklet_labels.xml", true);
    sequence.scans = IfPresent(path / "velodyne_points" / "data", false);
    return sequence;
  }
  if (IsKittiTracking(folder)) {
    const fs::path split = path.parent_path().parent_path();  // training/ or testing/
    const std::string id = sequence.name;
    sequence.layout = KittiLayout::kTracking;
    sequence.left_frames = path.string();
    sequence.right_frames = (split / "image_03" / id).string();
    sequence.calibration = (split / "calib" / (id + ".txt")).string();
    sequence.labels = IfPresent(split / "label_02" / (id + ".txt"), true);
    sequence.scans = IfPresent(split / "velodyne" / id, false);
    return sequence;
  }
  return std::nullopt;
}

}  // namespace attend
