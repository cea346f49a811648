// Feature plugins written in Python (docs/PYTHON.md, "Python features"): classes registered with
// attend.register_feature, or by a `.py` file named in `plugins:`, become features of the C++
// registry like any other (features/python_plugins.h). Each is computed under the GIL on a frame
// context whose images and maps are numpy arrays over the context's own buffers.
#pragma once

#include <pybind11/pybind11.h>

#include "pyramid/regions.h"

namespace attend::python {

namespace py = pybind11;

// The FeatureContext class, attend._attend._features (the registered classes), the
// registration functions, and the hooks through which the rest of attend reaches them.
void RegisterPythonFeatures(py::module_& m);

// A segmentation as a dict of arrays: `labels` (H x W int32), `regions` (a dict of per-region
// arrays: area, bbox (N x 4: x, y, width, height), colour (N x 3: S cos H, S sin H, V),
// saturation, intensity, perimeter), `boundaries` (M x 3: a, b, shared edge length) and
// `pyramid_levels`.
py::dict SegmentationDict(const Segmentation& segmentation);

}  // namespace attend::python
