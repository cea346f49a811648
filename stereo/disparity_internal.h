// The estimator's steps on their own, for its tests and benchmarks; not part of the API that
// plugins see (stereo/disparity.h).
#pragma once

#include <opencv2/core.hpp>

namespace attend {

// The ZNCC of the window around left (x, y) and right (x - d, y), both CV_8UC1, computed
// directly from its definition (for tests): window x window pixels, borders replicated. 0 when
// either window is flat.
double DirectZncc(const cv::Mat& left, const cv::Mat& right, int x, int y, int d, int window);

// The ZNCC slice of disparity d for every pixel (CV_32FC1), by box filtering, as the estimator
// computes it; pixels whose right window would leave the image (x - d < 0) get -1.
void ZnccSlice(const cv::Mat& left, const cv::Mat& right, int d, int window, cv::Mat* out);

// The left-right consistency check: a left pixel x with disparity d whose match x - round(d)
// lies outside the image, or whose right-view disparity there differs from d by more than
// `tolerance`, is set to -1 (invalid). `right_view` is the right image's disparity map.
void CheckLeftRight(const cv::Mat& right_view, int tolerance, cv::Mat* disparity);

// Fills invalid (negative) pixels from the nearest valid pixels on their row, taking the
// smaller (farther) disparity of the two sides, as occluded pixels see the background; a row
// without valid pixels becomes 0.
void FillInvalidDisparities(cv::Mat* disparity);

// Makes every estimator use its portable kernels (true) or, where the processor has AVX2, the
// AVX2 ones (false, the default). Both give the same maps, bit for bit; tests compare them.
// Not thread-safe: for tests only.
void UsePortableDisparityKernels(bool portable);

}  // namespace attend
