// The controller of `attend disparity` (SPEC 2.3, 3.2; docs/DISPARITY.md): the dense disparity
// map of one rectified stereo pair, written as PFM, with the Middlebury bad-pixel rates of
// SPEC 4 when ground truth is given. The command only parses its arguments and options.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "stereo/disparity.h"

namespace attend {

struct DisparityRequest {
  std::string left;  // read as 8-bit images (io/disparity_files.h ReadStereoImage)
  std::string right;
  std::string out;           // the .pfm to write; replaced only once the new map is complete
  DisparityOptions options;  // valid (Check)
  std::string gt;            // optional ground truth of the left view
  double gt_scale = 1.0;     // its values are divided by this
  // With gt: the regions of the left image's BIP segmentation larger than this share of the
  // image are scored as targets (app/region_disparity.h); 0: not.
  double regions = 0.0;
};

// Reads and checks every input before computing or writing anything, computes the map, writes
// it and returns the report `attend disparity` prints: the inputs, the size, the estimator's
// milliseconds and buffers, the options and, with ground truth, bad1 and bad2. InputError
// naming the file for unreadable or mismatched inputs or a range not below the width;
// OutputError when the map cannot be written.
nlohmann::json EstimateDisparity(const DisparityRequest& request);

}  // namespace attend
