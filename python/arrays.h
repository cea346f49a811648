// numpy arrays and cv::Mat in the attend Python module (docs/PYTHON.md, "Arrays").
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cstdint>
#include <opencv2/core.hpp>
#include <string>

#include "io/png_fast.h"

namespace attend::python {

namespace py = pybind11;

// An array over `mat`'s buffer, without a copy: the array holds a reference to the buffer
// (cv::Mat's reference count), so it stays valid after the C++ side has moved on; the stage that
// wrote it lets go of a buffer someone still holds before it writes the next frame
// (util/shared_mat.h). H x W for one channel, H x W x C for more. `writeable` false marks it
// read-only. An empty Mat gives None.
py::object MatArray(const cv::Mat& mat, bool writeable = true);

// The most pixels an image handed in may have: OpenCV's limit for decoded images
// (CV_IO_MAX_IMAGE_PIXELS), which attend's frame and image readers keep (io/png_fast.h).
inline constexpr uint64_t kMaxImagePixels = kMaxDecodedPixels;

// InputError naming `what` when `array` is not uint8 H x W or H x W x 3, is empty, or has more
// than kMaxImagePixels pixels. Reads the shape only: nothing is copied.
void CheckImage(const py::array& array, const std::string& what);

// `array` checked (CheckImage), then C-contiguous: itself, or a copy when it is a strided view.
py::array ContiguousImage(const py::array& array, const std::string& what);

// A cv::Mat header over a C-contiguous array's buffer, no copy; valid while the array lives.
// `what` names the array in errors. InputError as CheckImage, or when not C-contiguous.
cv::Mat ImageView(const py::array& array, const std::string& what);

// An 8-bit BGR image of its own: a grey array gets three equal channels (as frame files do),
// a BGR one is copied. InputError as CheckImage, before any copy.
cv::Mat BgrImage(const py::array& array, const std::string& what);

// A feature map from whatever a Python feature returned: anything numpy turns into a float32
// H x W array of `size`, copied into `out`. PluginError naming `what` otherwise.
void MapFromObject(const py::handle& object, cv::Size size, const std::string& what,
                   cv::Mat* out);

}  // namespace attend::python
