#include "python/arrays.h"

#include <cstdint>
#include <cstring>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "util/error.h"

namespace attend::python {

namespace {

std::string ShapeText(const py::array& array) {
  std::string text = "(";
  for (py::ssize_t i = 0; i < array.ndim(); ++i) {
    text += (i > 0 ? ", " : "") + std::to_string(array.shape(i));
  }
  return text + (array.ndim() == 1 ? ",)" : ")");
}

py::dtype DtypeOf(int depth) {
  switch (depth) {
    case CV_8U: return py::dtype::of<uint8_t>();
    case CV_8S: return py::dtype::of<int8_t>();
    case CV_16U: return py::dtype::of<uint16_t>();
    case CV_16S: return py::dtype::of<int16_t>();
    case CV_32S: return py::dtype::of<int32_t>();
    case CV_32F: return py::dtype::of<float>();
    default: return py::dtype::of<double>();
  }
}

}  // namespace

py::object MatArray(const cv::Mat& mat, bool writeable) {
  if (mat.empty()) return py::none();
  // The capsule owns a header that shares the buffer, so the buffer lives as long as the array.
  auto* held = new cv::Mat(mat);
  py::capsule owner(held, [](void* pointer) { delete static_cast<cv::Mat*>(pointer); });
  std::vector<py::ssize_t> shape = {mat.rows, mat.cols};
  std::vector<py::ssize_t> strides = {static_cast<py::ssize_t>(mat.step[0]),
                                      static_cast<py::ssize_t>(mat.step[1])};
  if (mat.channels() > 1) {
    shape.push_back(mat.channels());
    strides.push_back(static_cast<py::ssize_t>(mat.elemSize1()));
  }
  py::array array(DtypeOf(mat.depth()), shape, strides, held->data, owner);
  if (!writeable) {
    py::detail::array_proxy(array.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  }
  return array;
}

void CheckImage(const py::array& array, const std::string& what) {
  const bool grey = array.ndim() == 2;
  const bool bgr = array.ndim() == 3 && array.shape(2) == 3;
  if (!array.dtype().is(py::dtype::of<uint8_t>()) || !(grey || bgr)) {
    throw InputError(what + ": must be an 8-bit image, H x W (grey) or H x W x 3 (BGR) of "
                     "dtype uint8; got shape " + ShapeText(array) + " of dtype " +
                     py::str(array.dtype()).cast<std::string>());
  }
  if (array.shape(0) == 0 || array.shape(1) == 0) throw InputError(what + ": is empty");
  // Refused before any copy or OpenCV call: a 40000 x 40000 frame was copied (4.8 GB) and
  // then refused by OpenCV with its own RuntimeError, seconds later (issue 46).
  const uint64_t pixels = static_cast<uint64_t>(array.shape(0)) * array.shape(1);
  if (pixels > kMaxImagePixels) {
    throw InputError(what + ": an image of " + std::to_string(array.shape(1)) + " x " +
                     std::to_string(array.shape(0)) + " pixels (" + std::to_string(pixels) +
                     " in all) is more than attend takes: at most " +
                     std::to_string(kMaxImagePixels) +
                     " pixels (attend.MAX_IMAGE_PIXELS, OpenCV's limit for decoded images; "
                     "docs/LIMITS.md)");
  }
}

py::array ContiguousImage(const py::array& array, const std::string& what) {
  CheckImage(array, what);
  const py::array contiguous = py::array::ensure(array, py::array::c_style);
  if (!contiguous) throw InputError(what + ": cannot be read as an array");
  return contiguous;
}

cv::Mat ImageView(const py::array& array, const std::string& what) {
  CheckImage(array, what);
  if (!(array.flags() & py::array::c_style)) {
    throw InputError(what + ": must be C-contiguous (numpy.ascontiguousarray makes it so)");
  }
  return cv::Mat(static_cast<int>(array.shape(0)), static_cast<int>(array.shape(1)),
                 array.ndim() == 2 ? CV_8UC1 : CV_8UC3, const_cast<void*>(array.data()));
}

cv::Mat BgrImage(const py::array& array, const std::string& what) {
  const py::array contiguous = ContiguousImage(array, what);
  const cv::Mat view = ImageView(contiguous, what);
  cv::Mat image;
  if (view.channels() == 1) {
    cv::cvtColor(view, image, cv::COLOR_GRAY2BGR);
  } else {
    image = view.clone();
  }
  return image;
}

void MapFromObject(const py::handle& object, cv::Size size, const std::string& what,
                   cv::Mat* out) {
  // An array of another shape is refused before it is copied into float32.
  if (py::isinstance<py::array>(object)) {
    const auto array = py::reinterpret_borrow<py::array>(object);
    if (array.ndim() != 2 || array.shape(0) != size.height || array.shape(1) != size.width) {
      throw PluginError(what + ": returned a map of shape " + ShapeText(array) +
                        "; it must be (height, width) = (" + std::to_string(size.height) + ", " +
                        std::to_string(size.width) + "), the frame's working size");
    }
  }
  py::array_t<float, py::array::c_style | py::array::forcecast> map;
  try {
    map = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(object);
  } catch (py::error_already_set&) {
    map = {};
  }
  if (!map) {
    PyErr_Clear();
    throw PluginError(what + ": returned " +
                     py::str(py::type::of(object).attr("__name__")).cast<std::string>() +
                     ", which is not an array of numbers");
  }
  if (map.ndim() != 2 || map.shape(0) != size.height || map.shape(1) != size.width) {
    throw PluginError(what + ": returned a map of shape " + ShapeText(map) +
                     "; it must be (height, width) = (" + std::to_string(size.height) + ", " +
                     std::to_string(size.width) + "), the frame's working size");
  }
  out->create(size, CV_32FC1);
  std::memcpy(out->data, map.data(), sizeof(float) * size.area());
}

}  // namespace attend::python
