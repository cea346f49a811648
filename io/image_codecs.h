// PNG and JPEG read and written without OpenCV's imgcodecs (io/image_file.h uses them; other
// formats go through the optional OpenCV module, util/opencv_extra.h). libspng and
// libjpeg-turbo from Debian decode the formats of image sequences as cv::imdecode with
// IMREAD_COLOR does, pixel for pixel (tests/io/image_codecs_test.cc compares them on every
// variant), and faster (docs/PERFORMANCE.md, "Decoding").
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace attend {

// A PNG file as 8-bit BGR, as cv::imdecode(bytes, cv::IMREAD_COLOR) gives it: 16-bit samples
// keep their high byte, grey becomes three equal channels, a palette is expanded, alpha and
// transparency are dropped, no gamma is applied. Empty when `bytes` is not a PNG this decoder
// reads, or is damaged: the caller then asks OpenCV, whose answer (an image or an error) is
// the reference.
cv::Mat DecodePngColour(const std::vector<uchar>& bytes);

// A JPEG file as 8-bit BGR, as cv::imdecode(bytes, cv::IMREAD_COLOR) gives it (libjpeg's
// default decoding, grey as three equal channels, the EXIF orientation applied). Empty when
// `bytes` is not a JPEG this decoder reads (CMYK and YCCK are left to OpenCV), or is damaged.
cv::Mat DecodeJpegColour(const std::vector<uchar>& bytes);

// Encodes `image` (8-bit with 1, 3 (BGR) or 4 (BGRA) channels, or 16-bit with 1) as PNG with
// zlib level `level` (0-9); false for any other image.
bool EncodePng(const cv::Mat& image, int level, std::vector<uchar>* bytes);

// The EXIF orientation (1-8) in an EXIF block that starts with its TIFF header ("II" or "MM"),
// or 0 when it has none.
int ExifOrientation(const uchar* tiff, size_t size);

// Turns `image` as EXIF orientation `orientation` (1-8) says, as OpenCV does for JPEG files.
void ApplyExifOrientation(int orientation, cv::Mat* image);

}  // namespace attend
