// numpy arrays and cv::Mat in the attend Python module (docs/PYTHON.md, "Arrays").
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <opencv2/core.hpp>
#include <string>

namespace attend::python {

namespace py = pybind11;

// An array over `mat`'s buffer, without a copy: the array holds a reference to the buffer
// (cv::Mat's reference count), so it stays valid after the C++ side has moved on; the stage that
// wrote it lets go of a buffer someone still holds before it writes the next frame
// (util/shared_mat.h). H x W for one channel, H x W x C for more. `writeable` false marks it
// read-only. An empty Mat gives None.
py::object MatArray(const cv::Mat& mat, bool writeable = true);

// A cv::Mat header over a C-contiguous array's buffer, no copy; valid while the array lives.
// `what` names the array in errors. InputError when the array is not uint8 H x W or H x W x 3.
cv::Mat ImageView(const py::array& array, const std::string& what);

// An 8-bit BGR image of its own: a grey array gets three equal channels (as frame files do),
// a BGR one is copied. InputError as ImageView.
cv::Mat BgrImage(const py::array& array, const std::string& what);

// A feature map from whatever a Python feature returned: anything numpy turns into a float32
// H x W array of `size`, copied into `out`. PluginError naming `what` otherwise.
void MapFromObject(const py::handle& object, cv::Size size, const std::string& what,
                   cv::Mat* out);

}  // namespace attend::python
