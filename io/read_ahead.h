// Reading one frame ahead: a source whose next frame is read and decoded on a thread of its
// own while the caller works on the current one.
#pragma once

#include <memory>

#include "io/frame_source.h"

namespace attend {

// `source` read one frame ahead on a thread of its own: while the caller works on a frame, the
// next one is read and decoded (the bundled scene's 320x240 pair: 1.3 ms). The frames, their
// order and the errors (a bad frame's InputError, at the Next() that would have returned it)
// are those of `source`. For files and videos; a live source already has its capture thread.
std::unique_ptr<FrameSource> ReadAhead(std::unique_ptr<FrameSource> source);

}  // namespace attend
