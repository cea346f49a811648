// Stages on numpy images and the reading and writing of images and maps (python/bindings.h).
#include <memory>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cstdint>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

#include "app/home.h"
#include "config/param_block.h"
#include "features/disparity_feature.h"
#include "io/image_file.h"
#include "io/pfm.h"
#include "io/sequence.h"
#include "pipeline/still_saliency.h"
#include "pyramid/segmentation.h"
#include "python/arrays.h"
#include "python/bindings.h"
#include "python/python_features.h"
#include "stereo/disparity.h"
#include "util/error.h"

namespace attend::python {

namespace {

py::dict Saliency(const py::array& image, const AttendOptions& options, bool features) {
  const cv::Mat bgr = BgrImage(image, "image");
  std::vector<std::string> dropped;
  StillMaps maps;
  {
    const py::gil_scoped_release release;
    const StillSaliency still(options, AttendHome(), &dropped);
    maps = still.Compute(bgr, features, 0);
  }
  py::dict result;
  result["saliency"] = MatArray(maps.saliency);
  py::dict named;
  for (size_t i = 0; i < maps.features.size(); ++i) {
    named[py::str(maps.feature_names[i])] = MatArray(maps.features[i]);
  }
  result["features"] = named;
  result["left_out"] = dropped;
  result["working_size"] = py::make_tuple(maps.working_size.width, maps.working_size.height);
  return result;
}

// attend.imread: an image file as OpenCV reads it (BGR, or grey with `grey`), refused when
// it is cut short (io/image_file.h).
py::object ReadImage(const std::string& path, bool grey) {
  cv::Mat image;
  {
    const py::gil_scoped_release release;
    image = ReadNamedImageFile(path, grey ? cv::IMREAD_GRAYSCALE : cv::IMREAD_COLOR);
  }
  return MatArray(image);
}

// attend.imwrite: an 8-bit image (BGR or grey) to a file whose extension says the format.
void WriteImage(const std::string& path, const py::array& image) {
  // The contiguous array is held while its view is written (a strided array's copy would
  // otherwise be freed at the end of the statement).
  const py::array contiguous = ContiguousImage(image, "image");
  const cv::Mat view = ImageView(contiguous, "image");
  const py::gil_scoped_release release;
  WriteImageFile(path, view);
}

// attend.read_pfm and write_pfm: the run's lossless maps (io/pfm.h).
py::object ReadPfmArray(const std::string& path) {
  cv::Mat map;
  {
    const py::gil_scoped_release release;
    map = ReadPfm(path);
  }
  return MatArray(map);
}

void WritePfmArray(const std::string& path, const py::array& map) {
  // The size is checked on the shape, before the conversion to float32 copies the array.
  if (py::isinstance<py::array>(map) && map.ndim() >= 2) {
    const uint64_t pixels = static_cast<uint64_t>(map.shape(0)) * map.shape(1);
    if (pixels > kMaxImagePixels) {
      throw InputError(path + ": a map of " + std::to_string(map.shape(1)) + " x " +
                       std::to_string(map.shape(0)) + " pixels is more than attend writes: at "
                       "most " + std::to_string(kMaxImagePixels) +
                       " pixels (attend.MAX_IMAGE_PIXELS)");
    }
  }
  const auto floats = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(map);
  const bool one = floats && floats.ndim() == 2;
  const bool three = floats && floats.ndim() == 3 && floats.shape(2) == 3;
  if (!one && !three) {
    throw InputError(path + ": a PFM map is an array of numbers, H x W or H x W x 3");
  }
  const cv::Mat view(static_cast<int>(floats.shape(0)), static_cast<int>(floats.shape(1)),
                     one ? CV_32FC1 : CV_32FC3, const_cast<float*>(floats.data()));
  const py::gil_scoped_release release;
  WritePfm(path, view);
}

// attend.frames: a frame folder's files in frame order and one frame as `attend run` reads it.
std::vector<std::string> FrameFiles(const std::string& folder) {
  return ListFrameFiles(folder, folder);
}

py::object FrameFile(int index, const std::string& path) {
  cv::Mat frame;
  {
    const py::gil_scoped_release release;
    frame = ReadFrameFile(index, path);
  }
  return MatArray(frame);
}

py::dict Segment(const py::array& image, const AttendOptions& options) {
  const cv::Mat bgr = BgrImage(image, "image");
  Segmentation segmentation;
  {
    const py::gil_scoped_release release;
    Segmenter segmenter(options.segmentation);
    segmenter.Segment(bgr, &segmentation);
  }
  return SegmentationDict(segmentation);
}

// The disparity options of `overrides` ("disparity.KEY=VALUE"), read as `attend disparity`
// reads its --set.
DisparityOptions DisparityKeywords(const std::vector<std::string>& overrides) {
  ParamBlock root = ParamBlock::Parse("", "<keywords>");
  for (const std::string& assignment : overrides) root.Override(assignment);
  const ParamBlock block = root.Child("disparity");
  root.CheckNoUnknownKeys();
  const DisparityOptions options = ReadDisparityOptions(block);
  block.CheckNoUnknownKeys();
  return options;
}

py::object Disparity(const py::array& left, const py::array& right,
                     const std::vector<std::string>& overrides) {
  const DisparityOptions options = DisparityKeywords(overrides);
  const py::array left_array = ContiguousImage(left, "left");
  const py::array right_array = ContiguousImage(right, "right");
  const cv::Mat l = ImageView(left_array, "left");
  const cv::Mat r = ImageView(right_array, "right");
  // One estimator a thread, kept while the keywords stay the same: a user calls this in a loop,
  // and a fresh estimator a call took its cost volume and buffers from the kernel as new pages
  // each time, a third of the call at Middlebury sizes (docs/DISPARITY.md, "As a user calls
  // it"). cv2.StereoSGBM keeps its buffers in its object the same way.
  thread_local std::unique_ptr<DisparityEstimator> estimator;
  thread_local std::vector<std::string> estimator_keywords;
  if (!estimator || estimator_keywords != overrides) {
    estimator = std::make_unique<DisparityEstimator>(options);
    estimator_keywords = overrides;
  }
  cv::Mat disparity;
  {
    const py::gil_scoped_release release;
    estimator->Compute(l, r, &disparity);
  }
  return MatArray(disparity);
}

}  // namespace

void RegisterImages(py::module_& m) {
  m.attr("max_image_pixels") = kMaxImagePixels;
  m.def("saliency", [](const py::array& image, const Configuration& c, bool features) {
    return Saliency(image, c.options, features);
  });
  m.def("segment",
        [](const py::array& image, const Configuration& c) { return Segment(image, c.options); });
  m.def("disparity", &Disparity);
  m.def("imread", &ReadImage, py::arg("path"), py::arg("grey") = false);
  m.def("imwrite", &attend::python::WriteImage, py::arg("path"), py::arg("image"));
  m.def("read_pfm", &ReadPfmArray, py::arg("path"));
  m.def("write_pfm", &WritePfmArray, py::arg("path"), py::arg("map"));
  m.def("_frame_files", &FrameFiles);
  m.def("_frame_file", &FrameFile);
}

}  // namespace attend::python
