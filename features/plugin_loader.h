// Loading out-of-tree feature plugins (features/plugin_api.h, docs/PLUGINS.md).
#pragma once

#include <string>

#include "features/feature_map.h"

namespace attend {

// Loads the shared library at `path` and lets it register its features into `registry`. The
// library stays loaded until the program ends. A path ending in .py is a Python plugin
// (features/python_plugins.h). A missing or unloadable file, a missing
// `attend_plugin` symbol, an ABI version mismatch, or a feature name already taken: ConfigError
// naming the file (`where` says which configuration key listed it).
void LoadFeaturePlugin(const std::string& path, const std::string& where,
                       FeatureRegistry* registry);

}  // namespace attend
