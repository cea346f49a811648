// The PNG files image sequences are made of (8-bit grey, RGB or RGBA, not interlaced) decoded
// fast: libdeflate inflates the image data, and the row filters are undone with SSE2 where
// the processor has it. libspng, which DecodePngColour (io/image_codecs.h) uses for every
// other PNG, took 2.4 ms for a 320x240 frame of the bundled scene, two thirds of it in undoing
// the filters one byte at a time; this path takes about 0.8 ms for the same pixels
// (docs/PERFORMANCE.md, "Decoding").
#pragma once

#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

namespace attend {

// OpenCV refuses images of more pixels than this (CV_IO_MAX_IMAGE_PIXELS); attend's decoders
// leave larger ones to it, so that they are refused as before.
constexpr uint64_t kMaxDecodedPixels = uint64_t{1} << 30;

// Decodes `bytes` into `bgr` (8-bit BGR, as cv::imdecode with IMREAD_COLOR gives it) when it
// is a well-formed PNG of 8-bit grey, RGB or RGBA without interlacing; false for anything else
// (another kind, a damaged file: a chunk's CRC, the zlib stream, a filter type), which the
// caller then leaves to a complete decoder. Ancillary chunks are skipped; gamma and
// transparency are not applied, as OpenCV does not apply them with IMREAD_COLOR.
bool DecodeCommonPng(const std::vector<uchar>& bytes, cv::Mat* bgr);

// Makes DecodeCommonPng undo the filters with its portable code (true) or, where the processor
// has SSE2, the SSE2 code (false, the default). Both give the same pixels; tests compare them.
// Not thread-safe: for tests only.
void UsePortablePngFilters(bool portable);

}  // namespace attend
