#include "io/pfm.h"

#include <bit>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>

#include "util/error.h"
#include "util/file_checks.h"

namespace attend {

namespace {

// Reads the next whitespace-separated token of a PFM header.
bool ReadToken(std::istream& in, std::string* token) {
  token->clear();
  int c = in.get();
  while (c != EOF && std::isspace(c)) c = in.get();
  while (c != EOF && !std::isspace(c)) {
    token->push_back(static_cast<char>(c));
    c = in.get();
  }
  // `c` is the single whitespace character that ends the header field.
  return !token->empty();
}

// Parses all of `text` as a number; false when any of it is left or it is not one.
template <typename T>
bool ParseWhole(const std::string& text, T* value) {
  const char* end = text.data() + text.size();
  const auto [stop, error] = std::from_chars(text.data(), end, *value);
  return error == std::errc() && stop == end;
}

uint32_t ByteSwap(uint32_t v) {
  return (v >> 24) | ((v >> 8) & 0xff00u) | ((v << 8) & 0xff0000u) | (v << 24);
}

}  // namespace

cv::Mat ReadPfm(const std::string& path) {
  RequireRegularFile(path, "the PFM file", ExitStatus::kBadInput);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open the PFM file");
  std::string magic, width_text, height_text, scale_text;
  if (!ReadToken(in, &magic) || (magic != "Pf" && magic != "PF")) {
    throw InputError(path + ": not a PFM file (the header must start with Pf or PF)");
  }
  if (!ReadToken(in, &width_text) || !ReadToken(in, &height_text) || !ReadToken(in, &scale_text)) {
    throw InputError(path + ": truncated PFM header");
  }
  // Each field whole: "320abc" is not a width (std::stoi would read 320 and stop).
  int width = 0, height = 0;
  double scale = 0.0;
  if (!ParseWhole(width_text, &width) || !ParseWhole(height_text, &height) ||
      !ParseWhole(scale_text, &scale)) {
    throw InputError(path + ": malformed PFM header (width, height and scale must be numbers, got '" +
                     width_text + "', '" + height_text + "', '" + scale_text + "')");
  }
  if (width <= 0 || height <= 0 || width > (1 << 16) || height > (1 << 16) || scale == 0.0 ||
      !std::isfinite(scale)) {
    throw InputError(path + ": invalid PFM size " + width_text + "x" + height_text + " or scale " +
                     scale_text);
  }
  const int channels = magic == "PF" ? 3 : 1;
  // Check the size the header announces against the file before allocating for it.
  const std::streampos data_start = in.tellg();
  in.seekg(0, std::ios::end);
  const std::streamoff available = in.tellg() - data_start;
  in.seekg(data_start);
  const std::streamoff needed = static_cast<std::streamoff>(width) * height * channels * 4;
  if (available < needed) {
    throw InputError(path + ": truncated PFM data (the header announces " + width_text + "x" +
                     height_text + " but the file is too short)");
  }
  const bool file_little_endian = scale < 0.0;
  const bool host_little_endian = std::endian::native == std::endian::little;

  cv::Mat map(height, width, channels == 3 ? CV_32FC3 : CV_32FC1);
  const size_t row_bytes = static_cast<size_t>(width) * channels * sizeof(float);
  for (int row = height - 1; row >= 0; --row) {
    in.read(reinterpret_cast<char*>(map.ptr<float>(row)), static_cast<std::streamsize>(row_bytes));
    if (!in)
      throw InputError(path + ": truncated PFM data (expected " + std::to_string(height) +
                       " rows)");
    if (file_little_endian != host_little_endian) {
      auto* words = reinterpret_cast<uint32_t*>(map.ptr<float>(row));
      for (size_t i = 0; i < static_cast<size_t>(width) * channels; ++i)
        words[i] = ByteSwap(words[i]);
    }
  }
  return map;
}

cv::Mat ReadPfmOneChannel(const std::string& path, const std::string& what) {
  cv::Mat map = ReadPfm(path);
  if (map.channels() != 1) {
    throw InputError(path + ": " + what + " must be a one-channel PFM (Pf), not a three-channel one (PF)");
  }
  return map;
}

void WritePfm(const std::string& path, const cv::Mat& map) {
  ATTEND_CHECK(map.depth() == CV_32F && (map.channels() == 1 || map.channels() == 3))
      << "WritePfm needs CV_32FC1 or CV_32FC3, got type " << map.type();
  errno = 0;
  std::ofstream out(path, std::ios::binary);
  if (!out) throw OutputError(path + ": cannot write the PFM file");
  const bool little = std::endian::native == std::endian::little;
  out << (map.channels() == 3 ? "PF" : "Pf") << "\n"
      << map.cols << " " << map.rows << "\n"
      << (little ? "-1" : "1") << "\n";
  const size_t row_bytes = static_cast<size_t>(map.cols) * map.channels() * sizeof(float);
  for (int row = map.rows - 1; row >= 0; --row) {
    out.write(reinterpret_cast<const char*>(map.ptr<float>(row)),
              static_cast<std::streamsize>(row_bytes));
  }
  out.close();
  if (!out) {
    const int error_number = errno;
    throw OutputError(path + ": error while writing the PFM file" +
                      (error_number != 0 ? ": " + std::string(std::strerror(error_number)) : "") +
                      (error_number == ENOSPC ? " (the disk is full)" : ""));
  }
}

}  // namespace attend
