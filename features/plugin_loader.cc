#include "features/plugin_loader.h"

#include <dlfcn.h>

#include <filesystem>

#include "features/plugin_api.h"
#include "util/error.h"

namespace attend {

void LoadFeaturePlugin(const std::string& path, const std::string& where,
                       FeatureRegistry* registry) {
  const std::string prefix = where + ": plugin " + path + ": ";
  if (!std::filesystem::is_regular_file(path)) throw ConfigError(prefix + "no such file");
  // A relative path without a slash would make dlopen search the library path instead.
  const std::string load_path = std::filesystem::absolute(path).string();
  void* library = dlopen(load_path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (library == nullptr) {
    const char* reason = dlerror();
    throw ConfigError(prefix + "cannot be loaded: " + (reason != nullptr ? reason : "unknown"));
  }
  dlerror();
  void* symbol = dlsym(library, ATTEND_PLUGIN_ENTRY_SYMBOL);
  if (symbol == nullptr) {
    dlclose(library);
    throw ConfigError(prefix + "has no '" ATTEND_PLUGIN_ENTRY_SYMBOL
                               "' entry point (define it with ATTEND_PLUGIN, "
                               "features/plugin_api.h)");
  }
  const AttendPluginInfo* info = reinterpret_cast<AttendPluginEntry>(symbol)();
  if (info == nullptr || info->register_features == nullptr) {
    dlclose(library);
    throw ConfigError(prefix + "'" ATTEND_PLUGIN_ENTRY_SYMBOL "' returned no register function");
  }
  if (info->abi_version != ATTEND_PLUGIN_ABI_VERSION) {
    const int version = info->abi_version;
    dlclose(library);
    throw ConfigError(prefix + "was built for plugin ABI version " + std::to_string(version) +
                      ", this attend has version " + std::to_string(ATTEND_PLUGIN_ABI_VERSION) +
                      "; rebuild the plugin against this attend's headers");
  }
  // The library is never closed: its features' code and vtables are used until the end.
  registry->SetOrigin(path);
  try {
    info->register_features(registry);
  } catch (const ConfigError&) {
    registry->SetOrigin("built-in");
    throw;
  } catch (const std::exception& e) {
    registry->SetOrigin("built-in");
    throw ConfigError(prefix + "failed to register its features: " + e.what());
  }
  registry->SetOrigin("built-in");
}

}  // namespace attend
