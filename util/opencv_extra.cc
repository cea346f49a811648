#include "util/opencv_extra.h"

#include <dlfcn.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <mutex>

#include "util/error.h"

namespace attend::cvextra {

namespace {

namespace fs = std::filesystem;

std::mutex& ModuleMutex() {
  static std::mutex mutex;
  return mutex;
}

Module*& Instance() {
  static Module* module = nullptr;
  return module;
}

// Where the module may be: $ATTEND_OPENCV_EXTRA alone when set; else next to the running
// program, the build tree, the install tree.
std::vector<fs::path> Candidates() {
  if (const char* file = std::getenv("ATTEND_OPENCV_EXTRA"); file != nullptr && *file != '\0') {
    return {fs::path(file)};
  }
  std::vector<fs::path> candidates;
  std::error_code error;
  const fs::path program = fs::read_symlink("/proc/self/exe", error);
  if (!error) candidates.push_back(program.parent_path() / kLibraryName);
#ifdef ATTEND_OPENCV_EXTRA_BUILD_DIR
  candidates.push_back(fs::path(ATTEND_OPENCV_EXTRA_BUILD_DIR) / kLibraryName);
#endif
#ifdef ATTEND_OPENCV_EXTRA_INSTALL_DIR
  candidates.push_back(fs::path(ATTEND_OPENCV_EXTRA_INSTALL_DIR) / kLibraryName);
#endif
  return candidates;
}

}  // namespace

Module& Get(const std::string& what) {
  const std::lock_guard<std::mutex> lock(ModuleMutex());
  if (Instance() != nullptr) return *Instance();
  std::string tried;
  for (const fs::path& candidate : Candidates()) {
    tried += (tried.empty() ? "" : ", ") + candidate.string();
    std::error_code error;
    if (!fs::is_regular_file(candidate, error)) continue;
    // Never unloaded: OpenCV's modules keep global state.
    void* handle = dlopen(candidate.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (handle == nullptr) {
      const char* reason = dlerror();
      throw InternalError(what + " needs OpenCV's optional modules, but " + candidate.string() +
                          " cannot be loaded: " + (reason != nullptr ? reason : "unknown"));
    }
    auto entry = reinterpret_cast<EntryPoint>(dlsym(handle, kEntryPointName));
    Module* module = entry != nullptr ? entry(kAbiVersion) : nullptr;
    if (module == nullptr) {
      throw InternalError(what + " needs OpenCV's optional modules, but " + candidate.string() +
                          " is of another attend build (no entry point for interface version " +
                          std::to_string(kAbiVersion) + "); rebuild or reinstall attend");
    }
    Instance() = module;
    return *module;
  }
  throw InternalError(what + " needs OpenCV's optional modules, which attend loads from " +
                      std::string(kLibraryName) + ", but it is not there (looked for " + tried +
                      "); rebuild or reinstall attend, or set ATTEND_OPENCV_EXTRA to the file");
}

bool Loaded() {
  const std::lock_guard<std::mutex> lock(ModuleMutex());
  return Instance() != nullptr;
}

void SetOpenCvExtra(Module* module) {
  const std::lock_guard<std::mutex> lock(ModuleMutex());
  Instance() = module;
}

}  // namespace attend::cvextra
