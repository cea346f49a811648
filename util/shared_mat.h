// Maps handed out without a copy (the Python module's arrays share the buffers of the
// pipeline's last frame): before the next frame overwrites a buffer in place, a stage lets go of
// the ones that someone else still holds, so that those keep the values they were given.
#pragma once

#include <opencv2/core.hpp>

namespace attend {

// Releases `map` when its buffer has other references (cv::Mat's reference count), so that the
// next create() allocates a new one; a buffer only this header holds is kept for reuse.
inline void ReleaseIfShared(cv::Mat* map) {
  if (map->u != nullptr && map->u->refcount > 1) map->release();
}

}  // namespace attend
