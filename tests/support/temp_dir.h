// A fresh temporary folder per test, removed when the test ends.
#pragma once

#include <filesystem>
#include <string>

namespace attend::testing {

class TempDir {
 public:
  TempDir();
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  const std::filesystem::path& path() const { return path_; }
  // path() / name, as a string.
  std::string File(const std::string& name) const;
  // Writes `text` to path() / name and returns the full path.
  std::string Write(const std::string& name, const std::string& text) const;

 private:
  std::filesystem::path path_;
};

// The project root (ATTEND_HOME, set by ctest), for bundled configs and scenes.
std::string ProjectRoot();

// The reference data folder (shared/data beside the project, or ATTEND_SHARED_DATA): tests
// that use it skip when it is absent.
std::string SharedData();

}  // namespace attend::testing
