#include "io/image_file.h"

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <opencv2/imgcodecs.hpp>

#include "util/error.h"

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

cv::Mat ReadImageFile(const std::string& path, int flags, const std::string& where) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw InputError(where + ": cannot be read (missing or not readable)");
  std::vector<uchar> bytes((std::istreambuf_iterator<char>(file)),
                           std::istreambuf_iterator<char>());
  if (file.bad()) throw InputError(where + ": cannot be read");
  if (bytes.empty()) throw InputError(where + ": the file is empty");
  const std::string incomplete = IncompleteImage(bytes);
  if (!incomplete.empty()) throw InputError(where + ": " + incomplete);
  cv::Mat image;
  try {
    image = cv::imdecode(bytes, flags);
  } catch (const cv::Exception& e) {
    // OpenCV refuses images beyond its pixel limit, among others, by throwing.
    throw InputError(where + ": cannot be decoded: " + e.err);
  }
  if (image.empty()) {
    throw InputError(where + ": cannot be read or decoded as an image (corrupt or unsupported format)");
  }
  return image;
}

cv::Mat ReadNamedImageFile(const std::string& path, int flags, const std::string& what) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) {
    throw InputError(path + ": no such " + what + " file");
  }
  return ReadImageFile(path, flags, path);
}

void WriteImageFile(const std::string& path, const cv::Mat& image) {
  std::error_code error;
  const std::filesystem::path parent = std::filesystem::path(path).parent_path();
  if (!parent.empty()) std::filesystem::create_directories(parent, error);
  bool written = false;
  try {
    written = !error && cv::imwrite(path, image);
  } catch (const cv::Exception&) {
    written = false;
  }
  if (!written) throw OutputError(path + ": cannot write the image");
}

}  // namespace attend
