// The bindings of attend._attend (docs/PYTHON.md) by area, each area a file with one
// registration function that PYBIND11_MODULE calls (python/module.cc). A new binding goes in
// the file of its area, in that area's Register function; a new area is a file here, its
// function below and one line in python/module.cc. Every call that runs C++ work releases the
// GIL (py::gil_scoped_release), never around code that touches Python objects.
#pragma once

#include <pybind11/pybind11.h>

#include "pipeline/attend_options.h"

namespace attend::python {

namespace py = pybind11;

// Options bound for Python: the loaded configuration (its effective YAML by OptionsToYaml).
struct Configuration {
  AttendOptions options;
};

// The C++ errors as the package's exception classes (attend.ConfigError and the rest), each
// carrying the exit status the command line would give (configuration_bindings.cc).
void RegisterErrors(py::module_& m);

// attend.Configuration, the configuration files' paths, the home folder, the bundled sequence
// and the keys' descriptions (configuration_bindings.cc).
void RegisterConfiguration(py::module_& m);

// attend.Pipeline over frames handed in, attend.run over a source, and the reference loop of
// bench/python_bench.py (pipeline_bindings.cc).
void RegisterPipeline(py::module_& m);

// Stages on numpy images: saliency of a still image, segment, disparity; and reading and
// writing images, PFM maps and frame folders (image_bindings.cc).
void RegisterImages(py::module_& m);

// attend.Tracker (tracking_bindings.cc).
void RegisterTracking(py::module_& m);

// attend.eval_run, eval_fixations and compare, and the checks of a run folder's files that
// attend.read_run makes with the command line's readers (evaluation_bindings.cc).
void RegisterEvaluation(py::module_& m);

}  // namespace attend::python
