#include "io/image_file.h"

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>  // the IMREAD_ and IMWRITE_ constants only

#include "io/image_codecs.h"
#include "util/error.h"
#include "util/opencv_extra.h"
#include "util/strings.h"

namespace attend {

namespace {

bool IsJpeg(const std::vector<uchar>& b) {
  return b.size() >= 3 && b[0] == 0xFF && b[1] == 0xD8 && b[2] == 0xFF;
}

bool IsPng(const std::vector<uchar>& b) {
  static const uchar kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  return b.size() >= 8 && std::memcmp(b.data(), kSignature, 8) == 0;
}

}  // namespace

std::string IncompleteImage(const std::vector<uchar>& bytes) {
  if (IsJpeg(bytes)) {
    // The last start of scan; an end-of-image marker must come after it.
    size_t last_scan = std::string::npos;
    for (size_t i = 0; i + 1 < bytes.size(); ++i) {
      if (bytes[i] == 0xFF && bytes[i + 1] == 0xDA) last_scan = i;
    }
    if (last_scan == std::string::npos) return "a JPEG file without image data (no scan)";
    for (size_t i = last_scan + 2; i + 1 < bytes.size(); ++i) {
      if (bytes[i] == 0xFF && bytes[i + 1] == 0xD9) return "";
    }
    return "a JPEG file cut short (no end-of-image marker after its last scan; " +
           std::to_string(bytes.size()) + " bytes)";
  }
  if (IsPng(bytes)) {
    // A whole IEND chunk (length 0, type "IEND", its CRC) ends the image; decoders ignore
    // bytes after it, so only its absence is refused.
    static const uchar kIend[12] = {0, 0, 0, 0, 'I', 'E', 'N', 'D', 0xAE, 0x42, 0x60, 0x82};
    const auto end = std::search(bytes.rbegin(), bytes.rend(), std::rbegin(kIend),
                                 std::rend(kIend));
    if (end == bytes.rend()) {
      return "a PNG file cut short (no IEND chunk; " + std::to_string(bytes.size()) + " bytes)";
    }
  }
  return "";
}

cv::Mat DecodeImage(const std::vector<uchar>& bytes, int flags, const std::string& where) {
  // PNG and JPEG in colour, the frames of every sequence, without OpenCV's imgcodecs; what
  // these decoders do not read (another format or flag, a damaged file) is OpenCV's to answer.
  if (flags == cv::IMREAD_COLOR) {
    cv::Mat image;
    if (IsPng(bytes)) {
      image = DecodePngColour(bytes);
    } else if (IsJpeg(bytes)) {
      image = DecodeJpegColour(bytes);
    }
    if (!image.empty()) return image;
  }
  cv::Mat image;
  try {
    image = cvextra::Get(where + ": decoding this image").Decode(bytes, flags);
  } catch (const cv::Exception& e) {
    // OpenCV refuses images beyond its pixel limit, among others, by throwing.
    throw InputError(where + ": cannot be decoded: " + e.err);
  }
  if (image.empty()) {
    throw InputError(where + ": cannot be read or decoded as an image (corrupt or unsupported format)");
  }
  return image;
}

cv::Mat ReadImageFile(const std::string& path, int flags, const std::string& where) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw InputError(where + ": cannot be read (missing or not readable)");
  // In one block of the file's size and a byte (which meets the end), or in blocks of 64 kB
  // where the size is unknown; a byte at a time (istreambuf_iterator) took 0.12 ms for a
  // 120 kB frame.
  std::vector<uchar> bytes;
  std::error_code size_error;
  const auto size = std::filesystem::file_size(path, size_error);
  const size_t block = size_error ? size_t{1} << 16 : static_cast<size_t>(size) + 1;
  while (file) {
    const size_t had = bytes.size();
    bytes.resize(had + block);
    file.read(reinterpret_cast<char*>(bytes.data() + had), static_cast<std::streamsize>(block));
    bytes.resize(had + static_cast<size_t>(file.gcount()));
  }
  if (file.bad()) throw InputError(where + ": cannot be read");
  if (bytes.empty()) throw InputError(where + ": the file is empty");
  const std::string incomplete = IncompleteImage(bytes);
  if (!incomplete.empty()) throw InputError(where + ": " + incomplete);
  return DecodeImage(bytes, flags, where);
}

cv::Mat ReadNamedImageFile(const std::string& path, int flags, const std::string& what) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) {
    throw InputError(path + ": no such " + what + " file");
  }
  return ReadImageFile(path, flags, path);
}

cv::Mat ReadImageFileOrEmpty(const std::string& path, int flags) {
  try {
    return ReadImageFile(path, flags, path);
  } catch (const InputError&) {
    return cv::Mat();
  }
}

namespace {

// The zlib level of a PNG written with `params`: OpenCV's default (1) or its
// IMWRITE_PNG_COMPRESSION; -1 when other parameters ask for what only OpenCV does.
int PngLevel(const std::vector<int>& params) {
  if (params.empty()) return 1;
  if (params.size() == 2 && params[0] == cv::IMWRITE_PNG_COMPRESSION && params[1] >= 0 &&
      params[1] <= 9) {
    return params[1];
  }
  return -1;
}

bool IsPngPath(const std::string& path) {
  return Lowercase(std::filesystem::path(path).extension().string()) == ".png";
}

}  // namespace

bool EncodeImage(const std::string& extension, const cv::Mat& image, std::vector<uchar>* bytes,
                 const std::vector<int>& params) {
  const int level = PngLevel(params);
  if (Lowercase(extension) == ".png" && level >= 0 && EncodePng(image, level, bytes)) return true;
  try {
    return cvextra::Get("writing a " + extension + " image").Encode(extension, image, params, bytes);
  } catch (const cv::Exception&) {
    return false;
  }
}

bool WriteImage(const std::string& path, const cv::Mat& image, const std::vector<int>& params) {
  const int level = PngLevel(params);
  std::vector<uchar> bytes;
  if (IsPngPath(path) && level >= 0 && EncodePng(image, level, &bytes)) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    out.close();
    return static_cast<bool>(out);
  }
  try {
    return cvextra::Get("writing " + path).Write(path, image, params);
  } catch (const cv::Exception&) {
    return false;
  }
}

void WriteImageFile(const std::string& path, const cv::Mat& image) {
  std::error_code error;
  const std::filesystem::path parent = std::filesystem::path(path).parent_path();
  if (!parent.empty()) std::filesystem::create_directories(parent, error);
  if (error || !WriteImage(path, image)) throw OutputError(path + ": cannot write the image");
}

}  // namespace attend
