// attend._attend: the C++ part of the Python module `attend` (docs/PYTHON.md). The package's
// Python files (python/attend/) give it its public shape; the bindings are in files by area
// (python/bindings.h), registered here.
#include <pybind11/pybind11.h>

#include "python/bindings.h"
#include "python/python_features.h"
#include "util/opencv_extra.h"

// The optional OpenCV module's entry point, compiled into this module (python/CMakeLists.txt).
extern "C" attend::cvextra::Module* attend_opencv_extra(int abi_version);

PYBIND11_MODULE(_attend, m) {
  using namespace attend;
  using namespace attend::python;
  cvextra::SetOpenCvExtra(attend_opencv_extra(cvextra::kAbiVersion));
  m.doc() = "attend's C++ core (docs/PYTHON.md); use the package attend";
  m.attr("__version__") = ATTEND_VERSION;
  RegisterErrors(m);
  RegisterPythonFeatures(m);
  RegisterConfiguration(m);
  RegisterPipeline(m);
  RegisterImages(m);
  RegisterTracking(m);
  RegisterEvaluation(m);
}
