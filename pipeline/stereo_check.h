// What `attend run` checks and records of a stereo source (docs/STEREO3D.md): its calibration
// (form, file, whether the frames are rectified on the fly) and the row check of its first
// frame as handed out (stereo/row_check.h), summary.json's `stereo` block.
#pragma once

#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "io/frame_source.h"

namespace attend {

struct StereoSummary {
  std::string calibration_form;    // "full", "rectified", "nominal"; "" without a calibration
  std::string calibration_source;  // the file, or the sequence.yaml it came from
  bool rectified_on_the_fly = false;
  bool row_checked = false;     // the row check ran (sequence.check_rows, a stereo frame)
  double row_offset_px = 0.0;   // median |y_left - y_right|, pixels of the native frames
  int matches = 0;              // the features matched for it
  int frame = -1;               // the frame checked
  std::string note;             // why there is no verdict, when there is none
};

// The name of a calibration's form in summary.json: "full", "rectified", "nominal".
std::string CalibrationFormName(StereoCalibration::Form form);

// The stereo summary of `*source` (none for a monocular one). With `check_rows`
// the first frame is read and its rows measured at the working size, the offset scaled to
// native pixels; `*source` is then replaced by one that hands that frame out first. A median
// row offset above kMaxRowOffsetPx with enough matches is bad input: InputError naming the
// frame, its files, the offset, and what to do.
std::optional<StereoSummary> CheckStereoSource(bool check_rows,
                                               std::unique_ptr<FrameSource>* source);

// summary.json's `stereo` block.
nlohmann::ordered_json StereoSummaryJson(const StereoSummary& summary);

}  // namespace attend
