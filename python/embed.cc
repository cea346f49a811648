// The embedding library (features/python_plugins.h): the `attend` program loads it for the
// first `.py` file in `plugins:`. It starts an interpreter, imports the attend package from
// the folder it was given and lets the package's C++ part load the file into the program's
// feature registry. The interpreter lives until the program ends; between calls this library
// holds no GIL, so the features' Compute can take it from any thread.
#include <pybind11/embed.h>

#include <mutex>
#include <string>

namespace py = pybind11;

namespace attend {
class FeatureRegistry;
}

namespace {

std::mutex& EmbedMutex() {
  static std::mutex mutex;
  return mutex;
}

// Starts the interpreter once and gives up the GIL; Ctrl-C stays with attend's own handler.
void StartInterpreter() {
  if (Py_IsInitialized()) return;
  py::initialize_interpreter(/*init_signal_handlers=*/false);
  PyEval_SaveThread();
}

}  // namespace

// Returns 0 when the file's features are registered; else the exit status of the error (2: a
// configuration error, 4: the plugin's own code raised) with its message in `error`.
extern "C" __attribute__((visibility("default"))) int attend_python_embed_load(
    const char* package_parent, const char* path, const char* where,
    attend::FeatureRegistry* registry, std::string* error) {
  const std::lock_guard<std::mutex> lock(EmbedMutex());
  try {
    StartInterpreter();
    const py::gil_scoped_acquire gil;
    py::module_ module;
    try {
      py::module_ sys = py::module_::import("sys");
      py::list sys_path = sys.attr("path");
      bool present = false;
      for (const py::handle entry : sys_path) {
        if (py::str(entry).cast<std::string>() == package_parent) present = true;
      }
      if (!present) sys_path.insert(0, package_parent);
      module = py::module_::import("attend._attend");
      module.attr("_load_plugin_file")(py::capsule(registry, "attend.FeatureRegistry"), path,
                                       where);
      return 0;
    } catch (py::error_already_set& e) {
      const bool plugin = module && e.matches(module.attr("PluginError"));
      // The attend module turns its own errors into Python exceptions whose text is the
      // message attend prints.
      *error = std::string(e.value() ? py::str(e.value()).cast<std::string>() : e.what());
      if (error->find(path) == std::string::npos) {
        *error = std::string(where) + ": plugin " + path + ": " + *error;
      }
      return plugin ? 4 : 2;
    }
  } catch (const std::exception& e) {
    *error = std::string(where) + ": plugin " + path + ": the Python interpreter: " + e.what();
    return 2;
  }
}
