// Feature plugins written in Python (docs/PYTHON.md, "Python features"). The attend Python
// module (python/) implements them; this is how the rest of attend reaches it without depending
// on Python:
// - in a Python process, the module installs its hooks when it is imported: a `.py` file in
//   `plugins:` is run in that interpreter, and the features registered with
//   attend.register_feature join every registry;
// - in the `attend` program, the first `.py` file in `plugins:` loads the embedding library
//   (libattend_python_embed.so, beside the module), which starts an interpreter, imports the
//   module and runs the file. A configuration without a Python plugin never loads Python.
#pragma once

#include <string>

#include "features/feature_map.h"

namespace attend {

struct PythonFeatureHooks {
  // Runs the Python file `path` and adds the features it registered to `registry`;
  // ConfigError naming `where` and the file when it cannot be run.
  void (*load_file)(const std::string& path, const std::string& where,
                    FeatureRegistry* registry) = nullptr;
  // Adds every feature registered from Python so far to `registry`.
  void (*add_registered)(FeatureRegistry* registry) = nullptr;
};

// Installed by the Python module when it is imported.
void SetPythonFeatureHooks(const PythonFeatureHooks& hooks);

// True for a plugin path that names a Python file (ends in .py).
bool IsPythonPlugin(const std::string& path);

// Loads the Python plugin file at `path` (`where`: the configuration key that lists it) into
// `registry`: through the hooks when the module is loaded, else through the embedding library.
// ConfigError naming `where` and the file when Python, the module or the file cannot be used.
void LoadPythonFeaturePlugin(const std::string& path, const std::string& where,
                             FeatureRegistry* registry);

// The features registered from Python, when the module is loaded; nothing otherwise.
void AddPythonFeatures(FeatureRegistry* registry);

}  // namespace attend
