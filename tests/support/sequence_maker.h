// Writes small sequences in the SPEC 3.1 folder layout for tests.
#pragma once

#include <string>

namespace attend::testing {

// Writes `frames` frames of width x height into folder/left (and folder/right when stereo).
// Frame i is uniform with BGR value (i, 100, 200) on the left and (i, 50, 150) on the right,
// so a test can tell which frame it got. Returns `folder`.
std::string MakeFolderSequence(const std::string& folder, int frames, int width, int height,
                               bool stereo = true);

// Overwrites a frame file with bytes that are not an image.
void CorruptFrame(const std::string& folder, const std::string& view, int frame);

}  // namespace attend::testing
