// Frames stored as image files: listing a folder's frames in frame order and reading one as
// 8-bit BGR. Folder sources (io/folder_source.h), `attend saliency` and the Python module read
// frames through these.
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace attend {

// The frame files of a folder, in frame order: regular files ending in .png, .jpg, .jpeg, .ppm
// or .pgm (any letter case), sorted by file name byte by byte; everything else is ignored.
// Frame i is the i-th path. `what` starts error messages. InputError when the folder is
// missing, not a folder or cannot be listed; an empty list is not an error here.
std::vector<std::string> ListFrameFiles(const std::string& folder, const std::string& what);

// The file extensions ListFrameFiles accepts, lower case with the dot.
const std::vector<std::string>& FrameFileExtensions();

// Reads frame file `path` as 8-bit BGR (grey gets three equal channels, 16-bit keeps the high
// byte, JPEG EXIF orientation applied). InputError "frame INDEX (PATH): ..." when it cannot be
// read or decoded.
cv::Mat ReadFrameFile(int index, const std::string& path);

}  // namespace attend
