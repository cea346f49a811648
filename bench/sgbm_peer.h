// OpenCV's StereoSGBM as the benchmarks run it (disparity_bench, loop_bench): the parameters
// of OpenCV's samples/cpp/stereo_match.cpp with a 5x5 block and the penalties the OpenCV
// documentation recommends.
#pragma once

#include <opencv2/calib3d.hpp>

namespace attend::bench {

constexpr int kSgbmBlockSize = 5;
constexpr int kSgbmPreFilterCap = 63;
constexpr int kSgbmUniquenessRatio = 10;
constexpr int kSpeckleWindowSize = 100;
constexpr int kSpeckleRange = 32;
constexpr int kDisp12MaxDiff = 1;

// numDisparities for OpenCV: `max_disparity` rounded up to a multiple of 16, as OpenCV needs.
inline int OpenCvDisparities(int max_disparity) { return (max_disparity + 15) / 16 * 16; }

// MODE_SGBM with blockSize `block` and penalties `p1`, `p2`, the other parameters as above.
inline cv::Ptr<cv::StereoSGBM> MakeStereoSgbm(int max_disparity, int block, int p1, int p2) {
  return cv::StereoSGBM::create(0, OpenCvDisparities(max_disparity), block, p1, p2,
                                kDisp12MaxDiff, kSgbmPreFilterCap, kSgbmUniquenessRatio,
                                kSpeckleWindowSize, kSpeckleRange, cv::StereoSGBM::MODE_SGBM);
}

// MODE_SGBM with P1 = 8 cn blockSize^2 and P2 = 32 cn blockSize^2 for `channels` cn.
inline cv::Ptr<cv::StereoSGBM> MakeStereoSgbm(int max_disparity, int channels) {
  const int area = kSgbmBlockSize * kSgbmBlockSize;
  return MakeStereoSgbm(max_disparity, kSgbmBlockSize, 8 * channels * area,
                        32 * channels * area);
}

}  // namespace attend::bench
