// KITTI's own layouts as frame sources (io/kitti_layout.h, docs/SEQUENCES.md): a raw drive
// folder or a tracking sequence's image_02/NNNN given as sequence.folder (`attend run
// --sequence`). The left frames are image_02's, the right image_03's, paired by file name; the
// stereo calibration comes from KITTI's own files (a --calib file wins), and the frame rate is
// KITTI's 10 Hz.
#pragma once

#include <memory>

#include "io/frame_source.h"
#include "io/kitti_layout.h"
#include "io/sequence_options.h"

namespace attend {

// The source of `sequence`, found by FindKittiSequence(options.source.folder). InputError
// naming the folder or file: no frames, image_02 and image_03 that differ in count or names, a
// missing or malformed calibration (unless sequence.calib is set).
std::unique_ptr<FrameSource> OpenKittiSource(const SequenceOptions& options,
                                             const KittiSequence& sequence);

// KITTI records at 10 frames a second (devkit readme).
inline constexpr double kKittiFps = 10.0;

}  // namespace attend
