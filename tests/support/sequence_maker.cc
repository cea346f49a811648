#include "tests/support/sequence_maker.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>

namespace attend::testing {

namespace {
std::string FramePath(const std::string& folder, const std::string& view, int frame) {
  char name[32];
  std::snprintf(name, sizeof(name), "%06d.png", frame);
  return (std::filesystem::path(folder) / view / name).string();
}
}  // namespace

std::string MakeFolderSequence(const std::string& folder, int frames, int width, int height,
                               bool stereo) {
  std::filesystem::create_directories(std::filesystem::path(folder) / "left");
  if (stereo) std::filesystem::create_directories(std::filesystem::path(folder) / "right");
  for (int i = 0; i < frames; ++i) {
    cv::imwrite(FramePath(folder, "left", i),
                cv::Mat(height, width, CV_8UC3, cv::Scalar(i, 100, 200)));
    if (stereo) {
      cv::imwrite(FramePath(folder, "right", i),
                  cv::Mat(height, width, CV_8UC3, cv::Scalar(i, 50, 150)));
    }
  }
  return folder;
}

void CorruptFrame(const std::string& folder, const std::string& view, int frame) {
  std::ofstream out(FramePath(folder, view, frame), std::ios::binary | std::ios::trunc);
  out << "this is not a PNG file";
}

}  // namespace attend::testing
