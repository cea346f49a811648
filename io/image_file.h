// Reading image files strictly. OpenCV's JPEG and PNG decoders only warn when a file ends
// early and return the part they could decode (the rest grey or black): a frame cut short by
// an interrupted copy would be used as if whole. ReadImageFile refuses such files.
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace attend {

// Why `bytes`, the whole content of an image file, is incomplete, or "" when it is complete
// or of a format without such a check. JPEG: the end-of-image marker (FF D9) must follow the
// last start-of-scan marker (FF DA); entropy-coded data cannot hold FF D9 (every FF in it is
// followed by 00 or a restart marker), so a file cut short inside its scans has none there.
// PNG: a whole IEND chunk must be there (bytes after it are ignored, as decoders do).
std::string IncompleteImage(const std::vector<uchar>& bytes);

// Reads and decodes an image file with cv::imdecode `flags`. Throws InputError starting with
// `where` (a frame and path, or the path) when the file is missing, unreadable, incomplete
// (IncompleteImage) or not decodable.
cv::Mat ReadImageFile(const std::string& path, int flags, const std::string& where);

// ReadImageFile of a file the user named: InputError "PATH: no such WHAT file" when `path` is
// not a regular file, otherwise as ReadImageFile with the path as `where`.
cv::Mat ReadNamedImageFile(const std::string& path, int flags, const std::string& what = "image");

// Writes `image` with cv::imwrite (the format by the extension), creating the folders above it.
// OutputError "PATH: cannot write the image" when that fails.
void WriteImageFile(const std::string& path, const cv::Mat& image);

}  // namespace attend
