// Frames as a source gives them, before the working size: the checks every source's frames pass
// and the conversion of a decoded video or camera frame to 8-bit BGR, with errors that name the
// frame ("frame INDEX (PATH): ...").
#pragma once

#include <opencv2/core.hpp>
#include <string>

namespace attend {

// One frame at the size it has in the source.
struct NativeFrame {
  cv::Mat left;
  cv::Mat right;  // empty when monocular
  std::string left_path;
  std::string right_path;
};

// "frame INDEX (PATH)": where a frame's error messages start.
std::string FrameWhere(int index, const std::string& path);

// The checks every frame of a source passes: InputError "frame INDEX (PATH): size WxH differs
// from the first frame's ..." when `left` is not of size `first`, or "... differs from the left
// image's ..." when `right` (empty when monocular) is not of the left image's size.
void CheckFrameSizes(int index, const cv::Mat& left, const std::string& left_path,
                     const cv::Mat& right, const std::string& right_path, cv::Size first);

// A video frame as 8-bit BGR (grey and BGRA converted); InputError "frame INDEX (PATH): ..."
// for other depths or channel counts.
cv::Mat VideoFrameToBgr(const cv::Mat& frame, int index, const std::string& path);

// InputError "frame INDEX (PATH): width W is odd, ..." unless `both`, a side-by-side frame,
// splits into equal halves.
void CheckSideBySideWidth(const cv::Mat& both, int index, const std::string& path);

}  // namespace attend
