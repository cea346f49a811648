#include "io/native_frame.h"

#include <opencv2/imgproc.hpp>

#include "util/error.h"

namespace attend {

namespace {

std::string SizeText(cv::Size size) {
  return std::to_string(size.width) + "x" + std::to_string(size.height);
}

}  // namespace

std::string FrameWhere(int index, const std::string& path) {
  return "frame " + std::to_string(index) + " (" + path + ")";
}

void CheckFrameSizes(int index, const cv::Mat& left, const std::string& left_path,
                     const cv::Mat& right, const std::string& right_path, cv::Size first) {
  if (left.size() != first) {
    throw InputError(FrameWhere(index, left_path) + ": size " + SizeText(left.size()) +
                     " differs from the first frame's " + SizeText(first));
  }
  if (!right.empty() && right.size() != left.size()) {
    throw InputError(FrameWhere(index, right_path) + ": size " + SizeText(right.size()) +
                     " differs from the left image's " + SizeText(left.size()));
  }
}

// Video frames are normally 8-bit BGR already; other layouts are converted the way images are.
cv::Mat VideoFrameToBgr(const cv::Mat& frame, int index, const std::string& path) {
  if (frame.depth() != CV_8U) {
    throw InputError(FrameWhere(index, path) + ": unsupported sample depth (expected 8 bits)");
  }
  if (frame.channels() == 3) return frame;
  cv::Mat bgr;
  if (frame.channels() == 1) {
    cv::cvtColor(frame, bgr, cv::COLOR_GRAY2BGR);
  } else if (frame.channels() == 4) {
    cv::cvtColor(frame, bgr, cv::COLOR_BGRA2BGR);
  } else {
    throw InputError(FrameWhere(index, path) + ": unsupported number of channels " +
                     std::to_string(frame.channels()));
  }
  return bgr;
}

void CheckSideBySideWidth(const cv::Mat& both, int index, const std::string& path) {
  if (both.cols % 2 == 0) return;
  throw InputError(FrameWhere(index, path) + ": width " + std::to_string(both.cols) +
                   " is odd, so it cannot be split into equal left and right halves");
}

}  // namespace attend
