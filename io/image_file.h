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

// Decodes the whole content of an image file as cv::imdecode with `flags` does. PNG and JPEG
// in colour (IMREAD_COLOR) are decoded by io/image_codecs.h, everything else by OpenCV's
// imgcodecs in the optional module (util/opencv_extra.h). Throws InputError starting with
// `where` when the bytes cannot be decoded.
cv::Mat DecodeImage(const std::vector<uchar>& bytes, int flags, const std::string& where);

// Reads and decodes an image file (DecodeImage). Throws InputError starting with `where` (a
// frame and path, or the path) when the file is missing, unreadable, incomplete
// (IncompleteImage) or not decodable.
cv::Mat ReadImageFile(const std::string& path, int flags, const std::string& where);

// ReadImageFile of a file the user named: InputError "PATH: no such WHAT file" when `path` is
// not a regular file, otherwise as ReadImageFile with the path as `where`.
cv::Mat ReadNamedImageFile(const std::string& path, int flags, const std::string& what = "image");

// ReadImageFile, or an empty image when the file is missing or cannot be decoded (as cv::imread).
cv::Mat ReadImageFileOrEmpty(const std::string& path, int flags);

// Encodes `image` in the format of `extension` (".png", ".jpg"...) with cv::imwrite's
// `params`, as cv::imencode; PNG without other parameters than IMWRITE_PNG_COMPRESSION is
// written by io/image_codecs.h. False when it cannot be encoded.
bool EncodeImage(const std::string& extension, const cv::Mat& image, std::vector<uchar>* bytes,
                 const std::vector<int>& params = {});

// Writes `image` to `path` (the format by its extension) as cv::imwrite; false when that
// fails. PNG as in EncodeImage.
bool WriteImage(const std::string& path, const cv::Mat& image, const std::vector<int>& params = {});

// Writes `image` (WriteImage), creating the folders above it. OutputError "PATH: cannot write
// the image" when that fails.
void WriteImageFile(const std::string& path, const cv::Mat& image);

}  // namespace attend
