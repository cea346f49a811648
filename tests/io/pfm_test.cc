#include "io/pfm.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

#include "tests/support/error_message.h"
#include "tests/support/temp_dir.h"
#include "util/error.h"

namespace attend {
namespace {

using testing::ConfigErrorOf;
using testing::ErrorOf;
using testing::InputErrorOf;

constexpr float kInf = std::numeric_limits<float>::infinity();

// True when both maps have the same type, size and bits (so infinities compare equal).
bool SameBits(const cv::Mat& a, const cv::Mat& b) {
  if (a.type() != b.type() || a.size() != b.size()) return false;
  for (int row = 0; row < a.rows; ++row) {
    const size_t bytes = static_cast<size_t>(a.cols) * a.elemSize();
    if (std::memcmp(a.ptr(row), b.ptr(row), bytes) != 0) return false;
  }
  return true;
}

// A map whose every element is different, so a flipped or shifted read cannot pass.
cv::Mat Numbered(int rows, int cols, int type) {
  cv::Mat map(rows, cols, type);
  float* values = map.ptr<float>(0);
  for (size_t i = 0; i < map.total() * map.channels(); ++i) {
    values[i] = static_cast<float>(i) * 0.37f - 5.0f;
  }
  return map;
}

void AppendFloat(std::string* bytes, float value, bool big_endian) {
  uint32_t word = 0;
  std::memcpy(&word, &value, sizeof(word));
  for (int i = 0; i < 4; ++i) {
    const int shift = big_endian ? 24 - 8 * i : 8 * i;
    bytes->push_back(static_cast<char>((word >> shift) & 0xff));
  }
}

TEST(Pfm, OneChannelRoundTripKeepsInfinities) {
  testing::TempDir dir;
  cv::Mat map = Numbered(5, 7, CV_32FC1);
  map.at<float>(0, 0) = kInf;  // Middlebury's "unknown"
  map.at<float>(4, 6) = -kInf;
  map.at<float>(2, 3) = 1e-30f;
  const std::string path = dir.File("d.pfm");
  WritePfm(path, map);
  const cv::Mat read = ReadPfm(path);
  EXPECT_TRUE(SameBits(read, map));
  EXPECT_EQ(read.at<float>(0, 0), kInf);
  EXPECT_EQ(read.at<float>(4, 6), -kInf);
}

TEST(Pfm, ThreeChannelRoundTrip) {
  testing::TempDir dir;
  cv::Mat map = Numbered(3, 4, CV_32FC3);
  map.at<cv::Vec3f>(1, 2)[1] = kInf;
  const std::string path = dir.File("c.pfm");
  WritePfm(path, map);
  const cv::Mat read = ReadPfm(path);
  ASSERT_EQ(read.type(), CV_32FC3);
  EXPECT_TRUE(SameBits(read, map));
}

TEST(Pfm, WritesBottomRowFirstAsTheFormatRequires) {
  testing::TempDir dir;
  cv::Mat map(2, 1, CV_32FC1);
  map.at<float>(0, 0) = 1.0f;  // top
  map.at<float>(1, 0) = 2.0f;  // bottom
  const std::string path = dir.File("o.pfm");
  WritePfm(path, map);
  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_GE(bytes.size(), 8u);
  float first = 0.0f;
  std::memcpy(&first, bytes.data() + bytes.size() - 8, sizeof(first));
  EXPECT_EQ(first, 2.0f);
}

TEST(Pfm, ReadsABigEndianFile) {
  testing::TempDir dir;
  // 2x2, positive scale = big-endian; rows bottom first: bottom (3, 4), top (1, +inf).
  std::string bytes = "Pf\n2 2\n1.0\n";
  for (float value : {3.0f, 4.0f, 1.0f, kInf}) AppendFloat(&bytes, value, /*big_endian=*/true);
  const std::string path = dir.Write("be.pfm", bytes);
  const cv::Mat map = ReadPfm(path);
  ASSERT_EQ(map.type(), CV_32FC1);
  ASSERT_EQ(map.size(), cv::Size(2, 2));
  EXPECT_EQ(map.at<float>(0, 0), 1.0f);
  EXPECT_EQ(map.at<float>(0, 1), kInf);
  EXPECT_EQ(map.at<float>(1, 0), 3.0f);
  EXPECT_EQ(map.at<float>(1, 1), 4.0f);
}

TEST(Pfm, ReadsALittleEndianThreeChannelFileMadeByHand) {
  testing::TempDir dir;
  std::string bytes = "PF\n1 1\n-1.0\n";
  for (float value : {0.5f, -2.0f, 8.25f}) AppendFloat(&bytes, value, /*big_endian=*/false);
  const cv::Mat map = ReadPfm(dir.Write("le.pfm", bytes));
  ASSERT_EQ(map.type(), CV_32FC3);
  EXPECT_EQ(map.at<cv::Vec3f>(0, 0), cv::Vec3f(0.5f, -2.0f, 8.25f));
}

TEST(Pfm, TruncatedOrInvalidFilesAreBadInputNamingTheFile) {
  testing::TempDir dir;
  const std::string path = dir.File("t.pfm");
  WritePfm(path, Numbered(4, 4, CV_32FC1));
  std::filesystem::resize_file(path, std::filesystem::file_size(path) - 6);
  std::string message = InputErrorOf([&] { ReadPfm(path); });
  EXPECT_NE(message.find(path + ": truncated PFM data"), std::string::npos) << message;

  const std::string header_only = dir.Write("h.pfm", "Pf\n4");
  message = InputErrorOf([&] { ReadPfm(header_only); });
  EXPECT_NE(message.find(header_only + ": truncated PFM header"), std::string::npos) << message;

  const std::string not_pfm = dir.Write("p.pfm", "P6\n1 1\n255\nabc");
  message = InputErrorOf([&] { ReadPfm(not_pfm); });
  EXPECT_NE(message.find(not_pfm + ": not a PFM file"), std::string::npos) << message;

  const std::string missing = dir.File("missing.pfm");
  message = InputErrorOf([&] { ReadPfm(missing); });
  EXPECT_NE(message.find(missing + ": the PFM file does not exist"), std::string::npos) << message;
}

}  // namespace
}  // namespace attend
