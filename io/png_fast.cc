#include "io/png_fast.h"

#include <libdeflate.h>

#include <cstdint>
#include <cstring>
#include <memory>
#include <opencv2/imgproc.hpp>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace attend {

namespace {

// Scratch kept between calls up to this size (the inflated rows of a 1280x720 RGBA frame);
// larger images get their own and give it back.
constexpr size_t kKeptScratch = size_t{4} << 20;

bool g_portable_filters = false;

uint32_t Big32(const uchar* p) {
  return (uint32_t{p[0]} << 24) | (uint32_t{p[1]} << 16) | (uint32_t{p[2]} << 8) | p[3];
}

struct DecompressorFree {
  void operator()(libdeflate_decompressor* d) const { libdeflate_free_decompressor(d); }
};

enum Filter : uchar { kNone = 0, kSub = 1, kUp = 2, kAverage = 3, kPaeth = 4 };

int PaethPredictor(int a, int b, int c) {
  const int pa = std::abs(b - c);
  const int pb = std::abs(a - c);
  const int pc = std::abs(a + b - 2 * c);
  if (pa <= pb && pa <= pc) return a;
  return pb <= pc ? b : c;
}

// Undoes the filter of one row, one byte at a time. `in` holds the filtered row of `width`
// pixels of `in_bytes` bytes; `out` receives `out_channels` bytes a pixel: the pixel's bytes in
// reverse order (RGB -> BGR, alpha dropped) when out_channels is 3, as they are when it is 1.
// `above` is the previous row of `out` (zeros for the first row). Each channel of a PNG is
// filtered on its own, so reordering and dropping channels commutes with the filters.
void UnfilterRowPortable(Filter filter, const uchar* in, int in_bytes, const uchar* above,
                         uchar* out, int out_channels, int width) {
  for (int k = 0; k < out_channels; ++k) {
    const int from = out_channels == 1 ? 0 : 2 - k;
    int a = 0, c = 0;
    for (int x = 0; x < width; ++x) {
      const int raw = in[x * in_bytes + from];
      const int b = above[x * out_channels + k];
      int predicted = 0;
      switch (filter) {
        case kNone: break;
        case kSub: predicted = a; break;
        case kUp: predicted = b; break;
        case kAverage: predicted = (a + b) >> 1; break;
        case kPaeth: predicted = PaethPredictor(a, b, c); break;
      }
      const int value = (raw + predicted) & 0xFF;
      out[x * out_channels + k] = static_cast<uchar>(value);
      a = value;
      c = b;
    }
  }
}

#if defined(__SSE2__)

// Four bytes at `p` as 16-bit lanes 0-3 of a vector, the others zero.
inline __m128i Load4(const uchar* p) {
  uint32_t v;
  std::memcpy(&v, p, 4);
  return _mm_unpacklo_epi8(_mm_cvtsi32_si128(static_cast<int>(v)), _mm_setzero_si128());
}

inline __m128i Abs16(__m128i v) { return _mm_max_epi16(v, _mm_sub_epi16(_mm_setzero_si128(), v)); }

// UnfilterRowPortable for three output channels, a pixel at a time with its three channels in
// 16-bit lanes 0-2 (lane 3 carries whatever the fourth byte was and is never stored).
template <Filter kFilter>
void UnfilterRowBgrSse2(const uchar* in, int in_bytes, const uchar* above, uchar* out, int width) {
  const __m128i low_byte = _mm_set1_epi16(0xFF);
  __m128i a = _mm_setzero_si128();
  __m128i c = _mm_setzero_si128();
  for (int x = 0; x < width; ++x) {
    // RGB(A) -> BGR in lanes 0-2.
    const __m128i raw = _mm_shufflelo_epi16(Load4(in + x * in_bytes), _MM_SHUFFLE(3, 0, 1, 2));
    const __m128i b = Load4(above + 3 * x);
    __m128i predicted;
    if constexpr (kFilter == kNone) {
      predicted = _mm_setzero_si128();
    } else if constexpr (kFilter == kSub) {
      predicted = a;
    } else if constexpr (kFilter == kUp) {
      predicted = b;
    } else if constexpr (kFilter == kAverage) {
      predicted = _mm_srli_epi16(_mm_add_epi16(a, b), 1);
    } else {
      const __m128i pa = Abs16(_mm_sub_epi16(b, c));
      const __m128i pb = Abs16(_mm_sub_epi16(a, c));
      const __m128i pc = Abs16(_mm_sub_epi16(_mm_add_epi16(a, b), _mm_add_epi16(c, c)));
      // a where pa <= pb and pa <= pc; otherwise b where pb <= pc; otherwise c.
      const __m128i not_a = _mm_or_si128(_mm_cmpgt_epi16(pa, pb), _mm_cmpgt_epi16(pa, pc));
      const __m128i not_b = _mm_cmpgt_epi16(pb, pc);
      const __m128i b_or_c = _mm_or_si128(_mm_andnot_si128(not_b, b), _mm_and_si128(not_b, c));
      predicted = _mm_or_si128(_mm_andnot_si128(not_a, a), _mm_and_si128(not_a, b_or_c));
    }
    const __m128i value = _mm_and_si128(_mm_add_epi16(raw, predicted), low_byte);
    const uint32_t packed = static_cast<uint32_t>(_mm_cvtsi128_si32(_mm_packus_epi16(value, value)));
    std::memcpy(out + 3 * x, &packed, 3);
    a = value;
    c = b;
  }
}

#endif  // __SSE2__

// Undoes the filter of one row into `out` (UnfilterRowPortable).
void UnfilterRow(Filter filter, const uchar* in, int in_bytes, const uchar* above, uchar* out,
                 int out_channels, int width) {
#if defined(__SSE2__)
  if (out_channels == 3 && !g_portable_filters) {
    switch (filter) {
      case kNone: return UnfilterRowBgrSse2<kNone>(in, in_bytes, above, out, width);
      case kSub: return UnfilterRowBgrSse2<kSub>(in, in_bytes, above, out, width);
      case kUp: return UnfilterRowBgrSse2<kUp>(in, in_bytes, above, out, width);
      case kAverage: return UnfilterRowBgrSse2<kAverage>(in, in_bytes, above, out, width);
      case kPaeth: return UnfilterRowBgrSse2<kPaeth>(in, in_bytes, above, out, width);
    }
  }
#endif
  UnfilterRowPortable(filter, in, in_bytes, above, out, out_channels, width);
}

// What DecodeCommonPng needs of the chunks: the header's fields and the image data.
struct PngParts {
  uint32_t width = 0;
  uint32_t height = 0;
  int colour_type = 0;
  std::vector<uchar>* data = nullptr;  // the IDAT chunks' contents, concatenated
};

// Walks the chunks of `bytes`, checking each CRC; false for anything DecodeCommonPng leaves to
// the complete decoders.
bool ReadChunks(const std::vector<uchar>& bytes, PngParts* parts) {
  static const uchar kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  if (bytes.size() < 8 || std::memcmp(bytes.data(), kSignature, 8) != 0) return false;
  parts->data->clear();
  size_t at = 8;
  bool have_header = false;
  bool data_ended = false;  // a chunk other than IDAT came after the IDAT chunks
  while (true) {
    if (bytes.size() - at < 12) return false;
    const uchar* chunk = bytes.data() + at;
    const uint32_t length = Big32(chunk);
    if (length > 0x7FFFFFFFu || bytes.size() - at - 12 < length) return false;
    const uchar* type = chunk + 4;
    const uchar* body = chunk + 8;
    const uint32_t crc = static_cast<uint32_t>(libdeflate_crc32(0, type, length + 4));
    if (crc != Big32(body + length)) return false;
    at += 12 + size_t{length};
    const auto is = [type](const char* name) { return std::memcmp(type, name, 4) == 0; };
    if (!have_header) {
      if (!is("IHDR") || length != 13) return false;
      parts->width = Big32(body);
      parts->height = Big32(body + 4);
      const int depth = body[8];
      parts->colour_type = body[9];
      if (parts->width == 0 || parts->height == 0 || parts->width > 0x7FFFFFFFu ||
          parts->height > 0x7FFFFFFFu ||
          uint64_t{parts->width} * parts->height > kMaxDecodedPixels) {
        return false;
      }
      if (depth != 8 || (parts->colour_type != 0 && parts->colour_type != 2 &&
                         parts->colour_type != 6)) {
        return false;
      }
      if (body[10] != 0 || body[11] != 0 || body[12] != 0) return false;  // interlaced, or unknown
      have_header = true;
    } else if (is("IDAT")) {
      if (data_ended) return false;
      parts->data->insert(parts->data->end(), body, body + length);
    } else if (is("IEND")) {
      return !parts->data->empty();
    } else {
      if (!parts->data->empty()) data_ended = true;
      // A suggested palette in a true-colour file changes nothing; any other critical chunk
      // (upper-case first letter), and EXIF data, is for the complete decoders.
      if (is("PLTE") && parts->colour_type != 0) continue;
      if ((type[0] & 0x20) == 0 || is("eXIf")) return false;
    }
  }
}

// A vector kept for the next call unless it grew beyond kKeptScratch.
void TrimScratch(std::vector<uchar>* scratch) {
  if (scratch->capacity() > kKeptScratch) std::vector<uchar>().swap(*scratch);
}

}  // namespace

void UsePortablePngFilters(bool portable) { g_portable_filters = portable; }

bool DecodeCommonPng(const std::vector<uchar>& bytes, cv::Mat* bgr) {
  thread_local std::vector<uchar> data;
  thread_local std::vector<uchar> rows;
  thread_local std::unique_ptr<libdeflate_decompressor, DecompressorFree> decompressor(
      libdeflate_alloc_decompressor());
  if (decompressor == nullptr) return false;
  PngParts parts;
  parts.data = &data;
  const bool read = ReadChunks(bytes, &parts);
  if (!read) {
    TrimScratch(&data);
    return false;
  }
  const int width = static_cast<int>(parts.width);
  const int height = static_cast<int>(parts.height);
  const int in_bytes = parts.colour_type == 0 ? 1 : parts.colour_type == 2 ? 3 : 4;
  const size_t row_bytes = 1 + static_cast<size_t>(width) * in_bytes;
  const size_t expected = row_bytes * static_cast<size_t>(height);
  // Slack after the rows: the SSE2 code loads four bytes for a pixel of three.
  rows.resize(expected + 16);
  size_t produced = 0;
  const libdeflate_result result = libdeflate_zlib_decompress(
      decompressor.get(), data.data(), data.size(), rows.data(), expected, &produced);
  TrimScratch(&data);
  if (result != LIBDEFLATE_SUCCESS || produced != expected) {
    TrimScratch(&rows);
    return false;
  }
  const int out_channels = parts.colour_type == 0 ? 1 : 3;
  cv::Mat out(height, width, out_channels == 1 ? CV_8UC1 : CV_8UC3);
  // The row above the first is zeros, with the same slack.
  std::vector<uchar> zeros(static_cast<size_t>(width) * out_channels + 16, 0);
  bool ok = true;
  for (int y = 0; y < height; ++y) {
    const uchar* row = rows.data() + row_bytes * y;
    if (row[0] > kPaeth) {
      ok = false;
      break;
    }
    const uchar* above = y == 0 ? zeros.data() : out.ptr<uchar>(y - 1);
    UnfilterRow(static_cast<Filter>(row[0]), row + 1, in_bytes, above, out.ptr<uchar>(y),
                out_channels, width);
  }
  TrimScratch(&rows);
  if (!ok) return false;
  if (out_channels == 1) {
    cv::cvtColor(out, *bgr, cv::COLOR_GRAY2BGR);
  } else {
    *bgr = out;
  }
  return true;
}

}  // namespace attend
