// Where a sequence's stereo calibration comes from (docs/SEQUENCES.md, docs/STEREO3D.md), in
// this order: sequence.calib (`attend run --calib FILE`), SEQ/calib.yaml, sequence.yaml's
// focal_px and baseline_m (the nominal form), else none. Every source that opens a stereo pair
// asks here once it knows its native size (io/ranged_source.cc, io/live_source.cc).
#pragma once

#include <memory>

#include "io/frame_source.h"
#include "io/sequence_options.h"
#include "io/stereo_calibration.h"

namespace attend {

// Sets `info->calibration` for the source of `options` (info's stereo, folder, focal_px,
// baseline_m and native_size set already; a calibration its reader set, KITTI's, is kept
// unless sequence.calib is set) and returns the Rectifier of a full calibration
// (nullptr for the other forms and for none). A calibration file set on a monocular source:
// ConfigError. A calibration whose image size is not the frames' native size: InputError naming
// both. A bad calibration file: InputError (ReadStereoCalibration).
std::shared_ptr<const Rectifier> AttachCalibration(const SequenceOptions& options,
                                                   SequenceInfo* info);

}  // namespace attend
