// The configuration's `sequence:` section: the source (io/source_spec.h), the frame range and
// the working size. docs/SEQUENCES.md describes the layouts and rules.
#pragma once

#include <string>
#include <vector>

#include "io/source_spec.h"
#include "util/option_fields.h"

namespace attend {

struct SequenceOptions {
  // The source: sequence.folder ... sequence.gst_right, and the live section.
  SourceSpec source;

  // Frame range in source indices, inclusive; last_frame = -1 means to the end, and a last_frame
  // beyond the end stops at the end. A range that starts beyond the last frame is bad input.
  int first_frame = 0;
  int last_frame = -1;
  int stride = 1;  // take every stride-th frame from first_frame

  // Working size (io/working_size.h). "fit": scale, up or down, to the largest size that fits in
  // width x height keeping the aspect ratio (640x480 -> 320x240, 1280x720 -> 320x180,
  // 160x120 -> 320x240); "pixels" (the default): scale, up or down, to width x height pixels
  // keeping the aspect ratio, so that a wide frame keeps its detail (640x480 -> 320x240, KITTI's
  // 1242x375 -> 504x152 where fit gives 320x97); "stretch": exactly width x height; "native":
  // keep the source size.
  int width = 320;
  int height = 240;
  std::string resize = "pixels";

  // `attend run` measures the rows of the first stereo frame (stereo/row_check.h) and refuses a
  // pair whose rows do not match (not rectified); false skips the check.
  bool check_rows = true;

  // Empty when valid; otherwise names the field and the broken constraint: the source's
  // (SourceSpec::Check) and the range's and size's.
  std::string Check() const;
  // The range and size fields (util/option_fields.h), which Check and the configuration apply;
  // Check applies the ranges of width and height only unless resize is native (the
  // configuration always). The source's are SourceSpec::Fields().
  static const OptionFields<SequenceOptions>& Fields();
  // The values of `resize`.
  static const std::vector<std::string>& ResizeModes();
};

}  // namespace attend
