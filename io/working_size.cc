#include "io/working_size.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <opencv2/imgproc.hpp>
#include <string>

#include "util/error.h"

namespace attend {

namespace {

// What the loop holds per working pixel, about: 77.6 MB at 320x240 and 99.0 MB at 640x480
// (loop_bench's peak resident set) is 93 bytes a pixel more; 150 leaves room for the dumps,
// the trackers' pyramids and larger disparity ranges.
constexpr double kLoopBytesPerPixel = 150.0;

double PhysicalMemoryBytes() {
  const long pages = sysconf(_SC_PHYS_PAGES);
  const long page_size = sysconf(_SC_PAGESIZE);
  return pages > 0 && page_size > 0 ? static_cast<double>(pages) * page_size : 0.0;
}

std::string Gigabytes(double bytes) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.1f GB", bytes / 1e9);
  return text;
}

}  // namespace

cv::Size WorkingSize(const SequenceOptions& options, cv::Size native) {
  if (options.resize == "native") return native;
  if (options.resize == "stretch") return {options.width, options.height};
  if (options.resize == "pixels") {
    // The pixel count of width x height, the aspect ratio kept: a wide frame keeps its detail
    // (KITTI's 1242x375 is 504x152 rather than fit's 320x97), a 4:3 frame is as with fit.
    const double scale = std::sqrt(static_cast<double>(options.width) * options.height /
                                   (static_cast<double>(native.width) * native.height));
    return {std::max(1, static_cast<int>(std::lround(native.width * scale))),
            std::max(1, static_cast<int>(std::lround(native.height * scale)))};
  }
  // fit: the side that limits gets the box's size exactly, the other keeps the aspect ratio.
  const int64_t width_limited = static_cast<int64_t>(native.width) * options.height;
  const int64_t height_limited = static_cast<int64_t>(native.height) * options.width;
  if (width_limited >= height_limited) {
    const double height = static_cast<double>(native.height) * options.width / native.width;
    return {options.width, std::max(1, static_cast<int>(std::lround(height)))};
  }
  const double width = static_cast<double>(native.width) * options.height / native.height;
  return {std::max(1, static_cast<int>(std::lround(width))), options.height};
}

void SizeSequence(const SequenceOptions& options, cv::Size native, SequenceInfo* info) {
  info->native_size = native;
  info->size = WorkingSize(options, native);
  // A working size whose buffers cannot fit in this machine's memory ends in std::bad_alloc
  // (after seconds of work) or in the kernel's OOM killer: refuse it before any allocation.
  const double pixels = static_cast<double>(info->size.width) * info->size.height;
  const double needed = pixels * kLoopBytesPerPixel;
  const double memory = PhysicalMemoryBytes();
  if (memory > 0.0 && needed > memory) {
    const std::string size =
        std::to_string(info->size.width) + "x" + std::to_string(info->size.height);
    const std::string message =
        "the working size " + size + " (" + std::to_string(static_cast<int64_t>(pixels)) +
        " pixels) would need about " + Gigabytes(needed) + " (about " +
        std::to_string(static_cast<int>(kLoopBytesPerPixel)) + " bytes a pixel), more than " +
        "this machine's " + Gigabytes(memory) + " of memory";
    if (options.resize == "native") {
      throw InputError(message + "; the frames are " + std::to_string(native.width) + "x" +
                       std::to_string(native.height) +
                       ": use sequence.resize fit with a smaller sequence.width and height");
    }
    throw ConfigError(message + "; lower sequence.width and sequence.height");
  }
  info->scale_x = static_cast<double>(info->size.width) / native.width;
  info->scale_y = static_cast<double>(info->size.height) / native.height;
}

cv::Mat ToWorkingSize(const cv::Mat& image, cv::Size size) {
  if (image.size() == size) return image.isContinuous() ? image : image.clone();
  const bool shrinking = size.width <= image.cols && size.height <= image.rows;
  cv::Mat resized;
  cv::resize(image, resized, size, 0, 0, shrinking ? cv::INTER_AREA : cv::INTER_LINEAR);
  return resized;
}

}  // namespace attend
