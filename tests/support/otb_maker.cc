#include "tests/support/otb_maker.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

namespace attend::testing {

namespace {

namespace fs = std::filesystem;

// Smooth blotches of colour: uniform noise at an eighth of the size, enlarged.
cv::Mat Background(const cv::Size& size) {
  cv::Mat small(std::max(1, size.height / 8), std::max(1, size.width / 8), CV_8UC3);
  cv::RNG rng(20130623);
  rng.fill(small, cv::RNG::UNIFORM, 60, 200);
  cv::Mat background;
  cv::resize(small, background, size, 0, 0, cv::INTER_LINEAR);
  return background;
}

// A 4x4 checkerboard of two saturated colours, different for each square.
cv::Mat Texture(int side, int index) {
  static const cv::Scalar kColours[][2] = {{{20, 20, 230}, {230, 230, 30}},
                                           {{30, 200, 30}, {200, 30, 200}},
                                           {{230, 120, 20}, {20, 230, 230}}};
  const cv::Scalar* colours = kColours[index % 3];
  cv::Mat texture(side, side, CV_8UC3);
  const int cell = std::max(1, side / 4);
  for (int y = 0; y < side; ++y) {
    for (int x = 0; x < side; ++x) {
      const cv::Scalar& c = colours[((x / cell) + (y / cell)) % 2];
      texture.at<cv::Vec3b>(y, x) = cv::Vec3b(c[0], c[1], c[2]);
    }
  }
  return texture;
}

}  // namespace

std::vector<std::vector<cv::Rect>> MakeOtbSequence(const std::string& folder, int frames,
                                                   const cv::Size& size,
                                                   const std::vector<DrawnSquare>& squares,
                                                   bool numbered) {
  fs::create_directories(fs::path(folder) / "img");
  const cv::Mat background = Background(size);
  std::vector<std::vector<cv::Rect>> truth(squares.size());
  for (int i = 0; i < frames; ++i) {
    cv::Mat frame = background.clone();
    for (size_t s = 0; s < squares.size(); ++s) {
      const DrawnSquare& square = squares[s];
      const cv::Rect box(static_cast<int>(std::lround(square.start.x + i * square.step.x)),
                         static_cast<int>(std::lround(square.start.y + i * square.step.y)),
                         square.side, square.side);
      const cv::Rect inside = box & cv::Rect(0, 0, size.width, size.height);
      if (inside != box) throw std::logic_error("a drawn square leaves the frame");
      Texture(square.side, static_cast<int>(s)).copyTo(frame(box));
      truth[s].push_back(box);
    }
    char name[32];
    std::snprintf(name, sizeof(name), "%04d.jpg", i + 1);
    if (!cv::imwrite((fs::path(folder) / "img" / name).string(), frame,
                     {cv::IMWRITE_JPEG_QUALITY, 95})) {
      throw std::runtime_error("cannot write a frame in " + folder);
    }
  }
  for (size_t s = 0; s < squares.size(); ++s) {
    const std::string file = numbered || squares.size() > 1
                                 ? "groundtruth_rect." + std::to_string(s + 1) + ".txt"
                                 : std::string("groundtruth_rect.txt");
    std::ofstream out(fs::path(folder) / file);
    for (const cv::Rect& box : truth[s]) {
      out << box.x + 1 << '\t' << box.y + 1 << '\t' << box.width << '\t' << box.height << '\n';
    }
  }
  return truth;
}

}  // namespace attend::testing
