// What every stored source (folders, images, videos) shares: the frame range and stride, the
// size checks and the working size, over a reader that only knows how to read frame i of its
// kind at its native size. A new kind of stored source is a NativeReader
// (io/folder_source.cc and io/video_source.cc are two) handed to OpenRangedSource.
#pragma once

#include <memory>

#include "io/frame_source.h"
#include "io/native_frame.h"
#include "io/sequence_options.h"

namespace attend {

// Reads the frames of one kind of source at their native size. Open-time facts (stereo, name,
// fps, calibration, folder) go into the SequenceInfo its maker fills.
class NativeReader {
 public:
  virtual ~NativeReader() = default;
  // Frames in the source, or -1 when it cannot tell.
  virtual int Count() const = 0;
  // Reads frame `index` of the source; successive calls ask for increasing indices. False when
  // the source has no such frame; InputError when the frame exists but cannot be used.
  virtual bool Read(int index, NativeFrame* frame) = 0;
};

// The source of `reader`'s frames in `options`' range (first_frame, last_frame, stride), each
// checked against the first frame's size and handed out at the working size. The first frame is
// read here: it fixes the sizes (SizeSequence). `info` holds what `reader`'s maker learnt.
// InputError for a range that starts beyond the source's end, or a bad first frame.
std::unique_ptr<FrameSource> OpenRangedSource(const SequenceOptions& options,
                                              std::unique_ptr<NativeReader> reader,
                                              SequenceInfo info);

}  // namespace attend
