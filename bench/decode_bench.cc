// Decoding PNG and JPEG frames: attend's own path (io/image_codecs.h: libspng, libjpeg-turbo)
// against cv::imdecode, on the same bytes, in alternating rounds (the machine is shared, so the
// two are compared round by round). docs/PERFORMANCE.md, "Decoding".
//
//   decode_bench [--rounds N] [--repeat K] FILE...
//
// Each round decodes every file K times with one decoder, then with the other (which goes
// first alternates), and prints the mean milliseconds a decode of the whole set (a stereo pair:
// two files) for each; the last line gives the medians. Both must give identical pixels.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

#include "io/image_codecs.h"
#include "io/image_file.h"

namespace {

using Clock = std::chrono::steady_clock;

double Median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const size_t n = values.size();
  return n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

}  // namespace

int main(int argc, char** argv) {
  int rounds = 10, repeat = 20;
  std::vector<std::string> paths;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--rounds" && i + 1 < argc) {
      rounds = std::atoi(argv[++i]);
    } else if (arg == "--repeat" && i + 1 < argc) {
      repeat = std::atoi(argv[++i]);
    } else {
      paths.push_back(arg);
    }
  }
  if (paths.empty() || rounds < 1 || repeat < 1) {
    std::fprintf(stderr, "usage: decode_bench [--rounds N] [--repeat K] FILE...\n");
    return 2;
  }
  std::vector<std::vector<uchar>> files;
  for (const std::string& path : paths) {
    std::ifstream in(path, std::ios::binary);
    files.emplace_back((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const cv::Mat ours = attend::DecodeImage(files.back(), cv::IMREAD_COLOR, path);
    const cv::Mat opencv = cv::imdecode(files.back(), cv::IMREAD_COLOR);
    if (ours.size() != opencv.size() || cv::norm(ours, opencv, cv::NORM_INF) != 0.0) {
      std::fprintf(stderr, "%s: the decoders disagree\n", path.c_str());
      return 1;
    }
  }
  auto time_set = [&](bool ours) {
    const auto start = Clock::now();
    for (int k = 0; k < repeat; ++k) {
      for (const auto& bytes : files) {
        const cv::Mat image = ours ? attend::DecodeImage(bytes, cv::IMREAD_COLOR, "bench")
                                   : cv::imdecode(bytes, cv::IMREAD_COLOR);
        if (image.empty()) std::abort();
      }
    }
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count() / repeat;
  };
  std::vector<double> ours_ms, opencv_ms;
  std::printf("round  first   ours_ms  imdecode_ms\n");
  for (int round = 0; round < rounds; ++round) {
    const bool ours_first = round % 2 == 0;
    double a = 0.0, b = 0.0;
    if (ours_first) {
      a = time_set(true);
      b = time_set(false);
    } else {
      b = time_set(false);
      a = time_set(true);
    }
    ours_ms.push_back(a);
    opencv_ms.push_back(b);
    std::printf("%5d  %-6s  %7.3f  %11.3f\n", round, ours_first ? "ours" : "opencv", a, b);
  }
  std::printf("median ours %.3f ms, imdecode %.3f ms a set of %zu files (%.2fx)\n", Median(ours_ms),
              Median(opencv_ms), files.size(), Median(opencv_ms) / Median(ours_ms));
  return 0;
}
