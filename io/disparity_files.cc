#include "io/disparity_files.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <system_error>

#include "io/image_file.h"
#include "io/pfm.h"
#include "util/error.h"
#include "util/output_folder.h"
#include "util/strings.h"

namespace attend {

namespace {

namespace fs = std::filesystem;

std::string LowercaseExtension(const std::string& path) {
  return Lowercase(fs::path(path).extension().string());
}

}  // namespace

cv::Mat ReadStereoImage(const std::string& path) {
  return ReadNamedImageFile(path, cv::IMREAD_ANYCOLOR);
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
    const cv::Mat image = ReadNamedImageFile(path, cv::IMREAD_UNCHANGED, "ground-truth");
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
  ReplaceFile(out, "the map", [&](const std::string& temporary) {
    WritePfm(temporary, disparity);
    return true;
  });
}

}  // namespace attend
