#include "io/image_codecs.h"

#include <spng.h>

#include <csetjmp>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>

// jpeglib.h needs size_t and FILE declared first.
#include <jpeglib.h>

#include "io/png_fast.h"

namespace attend {

namespace {

struct SpngFree {
  void operator()(spng_ctx* ctx) const { spng_ctx_free(ctx); }
};

// Swaps the first and third byte of every 3-byte pixel of a row: RGB <-> BGR.
void SwapRedBlue(uchar* row, int width) {
  for (int x = 0; x < width; ++x) std::swap(row[3 * x], row[3 * x + 2]);
}

struct JpegErrors {
  jpeg_error_mgr manager;
  std::jmp_buf jump;
};

[[noreturn]] void JpegFail(j_common_ptr info) {
  std::longjmp(reinterpret_cast<JpegErrors*>(info->err)->jump, 1);
}

uint32_t Read32(const uchar* p, bool big_endian) {
  return big_endian ? (uint32_t{p[0]} << 24) | (uint32_t{p[1]} << 16) | (uint32_t{p[2]} << 8) | p[3]
                    : (uint32_t{p[3]} << 24) | (uint32_t{p[2]} << 16) | (uint32_t{p[1]} << 8) | p[0];
}

uint16_t Read16(const uchar* p, bool big_endian) {
  return static_cast<uint16_t>(big_endian ? (p[0] << 8) | p[1] : (p[1] << 8) | p[0]);
}

// libjpeg's part of DecodeJpegColour. Between setjmp and a longjmp from libjpeg only plain C
// objects live in this frame; `out` belongs to the caller. False on any libjpeg error or a
// colour space left to OpenCV.
bool DecodeJpegInto(const std::vector<uchar>& bytes, cv::Mat* out, int* orientation) {
  jpeg_decompress_struct info;
  JpegErrors errors;
  info.err = jpeg_std_error(&errors.manager);
  errors.manager.error_exit = JpegFail;
  // Warnings (a corrupt but decodable stream) stay silent, as decoding goes on either way.
  errors.manager.emit_message = [](j_common_ptr, int) {};
  if (setjmp(errors.jump) != 0) {
    jpeg_destroy_decompress(&info);
    return false;
  }
  jpeg_create_decompress(&info);
  jpeg_mem_src(&info, bytes.data(), static_cast<unsigned long>(bytes.size()));
  jpeg_save_markers(&info, JPEG_APP0 + 1, 0xFFFF);
  jpeg_read_header(&info, TRUE);
  if (info.num_components != 1 && info.num_components != 3) {
    jpeg_destroy_decompress(&info);
    return false;
  }
  if (static_cast<uint64_t>(info.image_width) * info.image_height > kMaxDecodedPixels) {
    jpeg_destroy_decompress(&info);
    return false;
  }
  *orientation = 0;
  for (jpeg_saved_marker_ptr marker = info.marker_list; marker != nullptr; marker = marker->next) {
    if (marker->marker == JPEG_APP0 + 1 && marker->data_length > 6 &&
        std::memcmp(marker->data, "Exif\0\0", 6) == 0) {
      *orientation = ExifOrientation(marker->data + 6, marker->data_length - 6);
      break;
    }
  }
  info.out_color_space = JCS_EXT_BGR;
  jpeg_start_decompress(&info);
  out->create(static_cast<int>(info.output_height), static_cast<int>(info.output_width), CV_8UC3);
  while (info.output_scanline < info.output_height) {
    JSAMPROW row = out->ptr<uchar>(static_cast<int>(info.output_scanline));
    jpeg_read_scanlines(&info, &row, 1);
  }
  jpeg_finish_decompress(&info);
  jpeg_destroy_decompress(&info);
  return true;
}

}  // namespace

cv::Mat DecodePngColour(const std::vector<uchar>& bytes) {
  cv::Mat fast;
  if (DecodeCommonPng(bytes, &fast)) return fast;
  std::unique_ptr<spng_ctx, SpngFree> ctx(spng_ctx_new(0));
  if (ctx == nullptr || spng_set_png_buffer(ctx.get(), bytes.data(), bytes.size()) != 0) {
    return cv::Mat();
  }
  spng_ihdr ihdr;
  if (spng_get_ihdr(ctx.get(), &ihdr) != 0) return cv::Mat();
  if (static_cast<uint64_t>(ihdr.width) * ihdr.height > kMaxDecodedPixels) return cv::Mat();
  size_t size = 0;
  if (spng_decoded_image_size(ctx.get(), SPNG_FMT_RGB8, &size) != 0) return cv::Mat();
  cv::Mat image(static_cast<int>(ihdr.height), static_cast<int>(ihdr.width), CV_8UC3);
  if (size != image.total() * image.elemSize()) return cv::Mat();
  // 16-bit samples to 8 bits keep the high byte (as libpng's strip_16 in OpenCV), and no
  // gamma or transparency is applied (flags 0).
  if (spng_decode_image(ctx.get(), image.data, size, SPNG_FMT_RGB8, 0) != 0) return cv::Mat();
  for (int y = 0; y < image.rows; ++y) SwapRedBlue(image.ptr<uchar>(y), image.cols);
  return image;
}

cv::Mat DecodeJpegColour(const std::vector<uchar>& bytes) {
  cv::Mat image;
  int orientation = 0;
  if (!DecodeJpegInto(bytes, &image, &orientation)) return cv::Mat();
  if (orientation > 1) ApplyExifOrientation(orientation, &image);
  return image;
}

int ExifOrientation(const uchar* tiff, size_t size) {
  if (size < 8) return 0;
  bool big_endian;
  if (tiff[0] == 'I' && tiff[1] == 'I') {
    big_endian = false;
  } else if (tiff[0] == 'M' && tiff[1] == 'M') {
    big_endian = true;
  } else {
    return 0;
  }
  if (Read16(tiff + 2, big_endian) != 42) return 0;
  const uint32_t ifd = Read32(tiff + 4, big_endian);
  if (ifd > size || size - ifd < 2) return 0;
  const int entries = Read16(tiff + ifd, big_endian);
  for (int i = 0; i < entries; ++i) {
    const size_t at = ifd + 2 + 12 * static_cast<size_t>(i);
    if (at + 12 > size) return 0;
    if (Read16(tiff + at, big_endian) != 0x0112) continue;
    const uint16_t type = Read16(tiff + at + 2, big_endian);
    if (type != 3) return 0;  // SHORT
    const int value = Read16(tiff + at + 8, big_endian);
    return value >= 1 && value <= 8 ? value : 0;
  }
  return 0;
}

void ApplyExifOrientation(int orientation, cv::Mat* image) {
  switch (orientation) {
    case 2:  // mirrored left-right
      cv::flip(*image, *image, 1);
      break;
    case 3:  // turned half round
      cv::flip(*image, *image, -1);
      break;
    case 4:  // mirrored top-bottom
      cv::flip(*image, *image, 0);
      break;
    case 5:
      cv::transpose(*image, *image);
      break;
    case 6:  // turned a quarter clockwise
      cv::transpose(*image, *image);
      cv::flip(*image, *image, 1);
      break;
    case 7:
      cv::transpose(*image, *image);
      cv::flip(*image, *image, -1);
      break;
    case 8:  // turned a quarter anticlockwise
      cv::transpose(*image, *image);
      cv::flip(*image, *image, 0);
      break;
    default:
      break;
  }
}

bool EncodePng(const cv::Mat& image, int level, std::vector<uchar>* bytes) {
  const int type = image.type();
  if (image.empty() || (type != CV_8UC1 && type != CV_8UC3 && type != CV_8UC4 && type != CV_16UC1)) {
    return false;
  }
  // Pixels in PNG order: RGB(A) instead of BGR(A), rows packed.
  cv::Mat pixels;
  if (type == CV_8UC3 || type == CV_8UC4) {
    pixels.create(image.size(), type);
    const int channels = image.channels();
    for (int y = 0; y < image.rows; ++y) {
      const uchar* in = image.ptr<uchar>(y);
      uchar* out = pixels.ptr<uchar>(y);
      for (int x = 0; x < image.cols; ++x) {
        out[channels * x] = in[channels * x + 2];
        out[channels * x + 1] = in[channels * x + 1];
        out[channels * x + 2] = in[channels * x];
        if (channels == 4) out[4 * x + 3] = in[4 * x + 3];
      }
    }
  } else {
    pixels = image.isContinuous() ? image : image.clone();
  }
  std::unique_ptr<spng_ctx, SpngFree> ctx(spng_ctx_new(SPNG_CTX_ENCODER));
  if (ctx == nullptr) return false;
  spng_set_option(ctx.get(), SPNG_ENCODE_TO_BUFFER, 1);
  spng_set_option(ctx.get(), SPNG_IMG_COMPRESSION_LEVEL, level);
  // As OpenCV's PNG writer does by default: every row with the Sub filter and zlib's run-length
  // strategy. libspng's own defaults (the best of five filters a row, the default strategy)
  // made the overlay dumps of the attention loop twice as slow to write (8.5 against 4 ms a
  // frame at 320x240) for files a little smaller.
  spng_set_option(ctx.get(), SPNG_FILTER_CHOICE, SPNG_FILTER_CHOICE_SUB);
  spng_set_option(ctx.get(), SPNG_IMG_COMPRESSION_STRATEGY, 3);  // Z_RLE
  spng_ihdr ihdr = {};
  ihdr.width = static_cast<uint32_t>(image.cols);
  ihdr.height = static_cast<uint32_t>(image.rows);
  ihdr.bit_depth = type == CV_16UC1 ? 16 : 8;
  ihdr.color_type = type == CV_8UC3   ? SPNG_COLOR_TYPE_TRUECOLOR
                    : type == CV_8UC4 ? SPNG_COLOR_TYPE_TRUECOLOR_ALPHA
                                      : SPNG_COLOR_TYPE_GRAYSCALE;
  if (spng_set_ihdr(ctx.get(), &ihdr) != 0) return false;
  const size_t size = pixels.total() * pixels.elemSize();
  if (spng_encode_image(ctx.get(), pixels.data, size, SPNG_FMT_PNG, SPNG_ENCODE_FINALIZE) != 0) {
    return false;
  }
  size_t length = 0;
  int error = 0;
  void* png = spng_get_png_buffer(ctx.get(), &length, &error);
  if (png == nullptr || error != 0) {
    std::free(png);
    return false;
  }
  const auto* begin = static_cast<const uchar*>(png);
  bytes->assign(begin, begin + length);
  std::free(png);
  return true;
}

}  // namespace attend
