#include "io/disparity_files.h"

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <system_error>

#include "io/image_file.h"
#include "io/pfm.h"
#include "util/error.h"

namespace attend {

namespace {

namespace fs = std::filesystem;

std::string LowercaseExtension(const std::string& path) {
  std::string text = fs::path(path).extension().string();
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

}  // namespace

cv::Mat ReadStereoImage(const std::string& path) {
  std::error_code error;
  if (!fs::is_regular_file(path, error)) throw InputError(path + ": no such image file");
  return ReadImageFile(path, cv::IMREAD_ANYCOLOR, path);
}

cv::Mat ReadDisparityGroundTruth(const std::string& path, double scale) {
  cv::Mat disparity;
  if (LowercaseExtension(path) == ".pfm") {
    const cv::Mat map = ReadPfm(path);
    if (map.channels() != 1) {
      throw InputError(path +
                       ": ground truth must be a one-channel PFM (Pf), not a three-channel "
                       "one");
    }
    disparity = map;
  } else {
    std::error_code error;
    if (!fs::is_regular_file(path, error)) throw InputError(path + ": no such ground-truth file");
    const cv::Mat image = ReadImageFile(path, cv::IMREAD_UNCHANGED, path);
    if (image.channels() != 1 || (image.depth() != CV_8U && image.depth() != CV_16U)) {
      throw InputError(path + ": ground truth must be one channel of 8 or 16 bits, got " +
                       std::to_string(image.channels()) + " channel(s) of " +
                       (image.depth() == CV_8U    ? "8"
                        : image.depth() == CV_16U ? "16"
                                                  : "other") +
                       " bits");
    }
    image.convertTo(disparity, CV_32F);
  }
  if (scale != 1.0) disparity /= scale;
  return disparity;
}

void WriteDisparityMap(const std::string& out, const cv::Mat& disparity) {
  const fs::path path(out);
  const fs::path parent = path.parent_path();
  std::error_code error;
  if (!parent.empty()) {
    fs::create_directories(parent, error);
    if (error) {
      throw OutputError(parent.string() + ": cannot create the folder (" + error.message() + ")");
    }
  }
  const fs::path temporary =
      parent / ("." + path.filename().string() + ".tmp" + std::to_string(getpid()));
  try {
    WritePfm(temporary.string(), disparity);
  } catch (const Error& e) {
    fs::remove(temporary, error);
    throw OutputError(out + ": cannot write the map (" + e.what() + ")");
  }
  fs::rename(temporary, path, error);
  if (error) {
    std::error_code ignored;
    fs::remove(temporary, ignored);
    throw OutputError(out + ": cannot write the map (" + error.message() + ")");
  }
}

}  // namespace attend
