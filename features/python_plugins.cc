#include "features/python_plugins.h"

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>
#include <mutex>
#include <vector>

#include "util/error.h"

namespace fs = std::filesystem;

namespace attend {

namespace {

std::mutex& HooksMutex() {
  static std::mutex mutex;
  return mutex;
}

PythonFeatureHooks& Hooks() {
  static PythonFeatureHooks hooks;
  return hooks;
}

PythonFeatureHooks CurrentHooks() {
  const std::lock_guard<std::mutex> lock(HooksMutex());
  return Hooks();
}

// The embedding library's entry point (python/embed.cc): starts the interpreter once, puts
// `package_parent` on sys.path, imports attend and loads the file; 0, or the exit status of
// what failed (2 or 4) with `error` set.
using EmbedLoad = int (*)(const char* package_parent, const char* path, const char* where,
                           FeatureRegistry* registry, std::string* error);

// The folders that may hold the attend package with its embedding library: $ATTEND_PYTHON_DIR,
// the build tree's, the installed one.
std::vector<std::string> PackageParents() {
  std::vector<std::string> parents;
  if (const char* dir = std::getenv("ATTEND_PYTHON_DIR"); dir != nullptr && *dir != '\0') {
    parents.push_back(dir);
  }
#ifdef ATTEND_PYTHON_BUILD_DIR
  parents.push_back(ATTEND_PYTHON_BUILD_DIR);
#endif
#ifdef ATTEND_PYTHON_INSTALL_DIR
  parents.push_back(ATTEND_PYTHON_INSTALL_DIR);
#endif
  return parents;
}

constexpr const char* kEmbedLibrary = "attend/libattend_python_embed.so";

EmbedLoad LoadEmbedding(const std::string& prefix, std::string* package_parent) {
  static std::mutex mutex;
  static EmbedLoad load = nullptr;
  static std::string parent;
  const std::lock_guard<std::mutex> lock(mutex);
  if (load != nullptr) {
    *package_parent = parent;
    return load;
  }
  std::string tried;
  for (const std::string& candidate : PackageParents()) {
    const fs::path library = fs::path(candidate) / kEmbedLibrary;
    tried += (tried.empty() ? "" : ", ") + library.string();
    if (!fs::is_regular_file(library)) continue;
    void* handle = dlopen(library.c_str(), RTLD_NOW | RTLD_GLOBAL);
    if (handle == nullptr) {
      const char* reason = dlerror();
      throw ConfigError(prefix + "the Python embedding library " + library.string() +
                        " cannot be loaded: " + (reason != nullptr ? reason : "unknown"));
    }
    void* symbol = dlsym(handle, "attend_python_embed_load");
    if (symbol == nullptr) {
      throw ConfigError(prefix + library.string() +
                        " has no attend_python_embed_load entry point (a different build?)");
    }
    load = reinterpret_cast<EmbedLoad>(symbol);
    parent = candidate;
    *package_parent = parent;
    return load;
  }
  throw ConfigError(prefix +
                    "a Python plugin needs attend's Python module, which this attend was not "
                    "built or installed with (looked for " +
                    (tried.empty() ? std::string("it nowhere: built without ATTEND_BUILD_PYTHON")
                                   : tried) +
                    "; set ATTEND_PYTHON_DIR to the folder that holds attend/)");
}

}  // namespace

void SetPythonFeatureHooks(const PythonFeatureHooks& hooks) {
  const std::lock_guard<std::mutex> lock(HooksMutex());
  Hooks() = hooks;
}

bool IsPythonPlugin(const std::string& path) { return fs::path(path).extension() == ".py"; }

void LoadPythonFeaturePlugin(const std::string& path, const std::string& where,
                             FeatureRegistry* registry) {
  const std::string prefix = where + ": plugin " + path + ": ";
  if (!fs::is_regular_file(path)) throw ConfigError(prefix + "no such file");
  const PythonFeatureHooks hooks = CurrentHooks();
  if (hooks.load_file != nullptr) {
    hooks.load_file(path, where, registry);
    return;
  }
  std::string package_parent;
  const EmbedLoad load = LoadEmbedding(prefix, &package_parent);
  std::string error;
  const int status = load(package_parent.c_str(), path.c_str(), where.c_str(), registry, &error);
  if (status == static_cast<int>(ExitStatus::kPlugin)) throw PluginError(error);
  if (status != 0) throw ConfigError(error);
}

void AddPythonFeatures(FeatureRegistry* registry) {
  const PythonFeatureHooks hooks = CurrentHooks();
  if (hooks.add_registered != nullptr) hooks.add_registered(registry);
}

}  // namespace attend
