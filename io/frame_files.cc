#include "io/frame_files.h"

#include <algorithm>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>

#include "io/image_file.h"
#include "io/native_frame.h"
#include "util/error.h"
#include "util/strings.h"

namespace attend {

namespace fs = std::filesystem;

const std::vector<std::string>& FrameFileExtensions() {
  static const std::vector<std::string> extensions = {".png", ".jpg", ".jpeg", ".ppm", ".pgm"};
  return extensions;
}

std::vector<std::string> ListFrameFiles(const std::string& folder, const std::string& what) {
  std::error_code error;
  if (!fs::exists(folder, error)) throw InputError(what + ": no such folder " + folder);
  if (!fs::is_directory(folder, error)) throw InputError(what + ": " + folder + " is not a folder");
  const std::vector<std::string>& extensions = FrameFileExtensions();
  std::vector<std::string> paths;
  try {
    for (const fs::directory_entry& entry : fs::directory_iterator(folder)) {
      if (!entry.is_regular_file()) continue;
      const std::string extension = Lowercase(entry.path().extension().string());
      if (std::find(extensions.begin(), extensions.end(), extension) != extensions.end()) {
        paths.push_back(entry.path().string());
      }
    }
  } catch (const fs::filesystem_error& e) {
    throw InputError(what + ": cannot list the frames in " + folder + ": " + e.what());
  }
  // By file name, byte by byte: the position in this list is the frame index.
  std::sort(paths.begin(), paths.end(), [](const std::string& a, const std::string& b) {
    return fs::path(a).filename().string() < fs::path(b).filename().string();
  });
  return paths;
}

cv::Mat ReadFrameFile(int index, const std::string& path) {
  // IMREAD_COLOR turns grey into three equal channels and 16-bit samples into 8-bit ones (the
  // high byte), so every later stage sees CV_8UC3.
  return ReadImageFile(path, cv::IMREAD_COLOR, FrameWhere(index, path));
}

}  // namespace attend
