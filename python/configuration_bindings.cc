// Configuration and errors of attend._attend (python/bindings.h).
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cstring>
#include <string>
#include <vector>

#include "app/home.h"
#include "config/param_block.h"
#include "pipeline/options_io.h"
#include "python/bindings.h"
#include "python/in_use.h"
#include "tracker/target_tracker.h"
#include "util/error.h"

namespace attend::python {

namespace {

// The configuration of `config` (a file; "" for the built-in defaults) with `overrides`
// ("key.path=value", as --set) applied in order: the command line's errors, word for word.
AttendOptions LoadConfiguration(const std::string& config,
                                const std::vector<std::string>& overrides) {
  if (!config.empty()) return LoadOptions(config, overrides);
  ParamBlock root = ParamBlock::Parse("", "<defaults>");
  for (const std::string& assignment : overrides) root.Override(assignment);
  return ReadOptions(root);
}

py::list DescribeKeys() {
  py::list keys;
  for (const FieldDescription& field : DescribeConfiguration()) {
    py::dict key;
    key["key"] = field.key;
    key["type"] = field.type;
    key["range"] = field.range;
    key["default"] = field.fallback;
    key["doc"] = field.doc;
    keys.append(key);
  }
  return keys;
}

// Raises `type` with `message`. A message may quote bytes of a damaged file that are not UTF-8
// (a JSON parser's "last read: ..."): they are shown as \xNN escapes, where PyErr_SetString
// would have dropped the whole message (issue 46).
template <typename Type>
void Raise(const py::exception<Type>& type, const char* message) {
  PyObject* text = PyUnicode_DecodeUTF8(message, static_cast<Py_ssize_t>(std::strlen(message)),
                                        "backslashreplace");
  if (text == nullptr) return;  // out of memory: that error is set
  PyErr_SetObject(type.ptr(), text);
  Py_DECREF(text);
}

}  // namespace

// The C++ errors as the package's exception classes (attend.ConfigError and the rest), each
// carrying the exit status the command line would give.
void RegisterErrors(py::module_& m) {
  static py::exception<Error> error(m, "Error");
  static py::exception<ConfigError> config(m, "ConfigError", error.ptr());
  static py::exception<OutputError> output(m, "OutputError", error.ptr());
  static py::exception<InputError> input(m, "InputError", error.ptr());
  static py::exception<PluginError> plugin(m, "PluginError", error.ptr());
  static py::exception<InternalError> internal(m, "InternalError", error.ptr());
  static py::exception<InUseError> in_use(m, "InUseError", error.ptr());
  py::register_exception_translator([](std::exception_ptr pointer) {
    try {
      if (pointer) std::rethrow_exception(pointer);
    } catch (const ConfigError& e) {
      Raise(config, e.what());
    } catch (const OutputError& e) {
      Raise(output, e.what());
    } catch (const InputError& e) {
      Raise(input, e.what());
    } catch (const PluginError& e) {
      Raise(plugin, e.what());
    } catch (const InternalError& e) {
      Raise(internal, e.what());
    } catch (const InUseError& e) {
      Raise(in_use, e.what());
    } catch (const Error& e) {
      Raise(error, e.what());
    }
  });
}

void RegisterConfiguration(py::module_& m) {
  py::class_<Configuration>(m, "Configuration")
      .def(py::init([](const std::string& config, const std::vector<std::string>& overrides) {
             return Configuration{LoadConfiguration(config, overrides)};
           }),
           py::arg("config"), py::arg("overrides"))
      .def("yaml", [](const Configuration& c) { return OptionsToYaml(c.options); });
  m.def("default_config_path", &DefaultConfigPath);
  m.def("segment_config_path", &SegmentConfigPath);
  m.def("track_config_path", [](const std::string& kind_name) {
    TrackerKind kind = TrackerKind::kBip;
    // An unknown kind is named by the configuration reader, with the kinds there are.
    return TrackerKindFromName(kind_name, &kind) ? TrackConfigPath(kind) : std::string();
  });
  m.def("home", &AttendHome);
  m.def("bundled_sequence", [](bool quiet) {
    const py::gil_scoped_release release;
    return EnsureBundledSequence(quiet);
  });
  m.def("describe_keys", &DescribeKeys);
}

}  // namespace attend::python
