// The controller of `attend saliency` (docs/FIXATIONS.md): the pre-attentive stage on
// still images, each on its own (pipeline/still_saliency.h), written as OUT/<stem>.pfm and
// OUT/<stem>.png at the image's size, OUT/saliency.json and, on request, every feature's map
// (OUT/features/<name>/<stem>.*) and the first attended regions (OUT/scanpath.json). The command
// only parses its arguments and lists the images.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "pipeline/attend_options.h"
#include "pipeline/still_saliency.h"
#include "util/error.h"

namespace attend {

struct SaliencyMapsRequest {
  std::vector<std::string> images;  // image files, their stems all different
  std::string out;                  // may hold other files: only these are written
  AttendOptions options;
  std::string home;          // the attend home (plugins' relative data paths)
  bool features = false;     // also every feature's normalised map
  int scanpath = 0;          // also the first K attended regions of each image
  ScanpathPoint scanpath_point = ScanpathPoint::kCentre;  // where each step lands
  std::string config_path;   // recorded in saliency.json
  std::string command_line;  // recorded in saliency.json
};

struct SaliencyMapsResult {
  int written = 0;                  // images with maps
  std::vector<std::string> failed;  // images that could not be read
};

// What a run of WriteSaliencyMaps tells as it goes: each feature left out because it needs
// stereo (before any image), and each image that cannot be read (the others still get maps).
struct SaliencyMapsObserver {
  std::function<void(const std::string& feature)> on_left_out;
  std::function<void(const InputError& error)> on_unreadable;
};

// ConfigError for features or plugins that cannot be used; InputError naming the file when an
// output cannot be written.
SaliencyMapsResult WriteSaliencyMaps(const SaliencyMapsRequest& request,
                                     const SaliencyMapsObserver& observer);

}  // namespace attend
