// The controller of `attend segment` (SPEC 3.2, docs/PYRAMID.md): BIP colour segmentation of
// still images, each written as OUT/<stem>.labels.png (16-bit labels), OUT/<stem>.regions.png
// (false colour) and OUT/<stem>.mean.png (region mean colours), then OUT/segment.json; with
// the quality measures of thesis 3.3.2 on request. The command only parses its arguments.
#pragma once

#include <functional>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "pyramid/metrics.h"
#include "pyramid/segmentation.h"

namespace attend {

struct SegmentRequest {
  std::vector<std::string> images;  // read as 8-bit BGR (grey replicated, 16 bits scaled)
  std::vector<std::string> stems;   // the output stem of each image, all different
  std::string out;                  // created if missing; may hold other files
  SegmentationOptions options;
  bool metrics = false;  // also F, Q and the shift variance
};

// One image once its files are written.
struct SegmentedImage {
  std::string path;
  cv::Size size;
  size_t regions = 0;
  int pyramid_levels = 0;
  double milliseconds = 0.0;
  std::optional<SegmentationQuality> quality;  // with `metrics`
  // With `metrics`, when the image is large enough for the thesis's shifts.
  std::optional<double> shift_variance;
};

// Segments every image in order and calls `on_image` after each (progress, a line of text).
// InputError naming the image when it cannot be read or has too many regions for 16-bit
// labels; OutputError naming the file that cannot be written. Files of images done stay.
void SegmentImages(const SegmentRequest& request,
                   const std::function<void(const SegmentedImage&)>& on_image);

}  // namespace attend
