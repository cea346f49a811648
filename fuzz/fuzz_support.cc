#include "fuzz/fuzz_support.h"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <opencv2/core.hpp>
#include <opencv2/core/utils/logger.hpp>
#include <sstream>

namespace attend::fuzz {

namespace fs = std::filesystem;

namespace {

[[noreturn]] void Stop(const std::string& message) {
  std::fprintf(stderr, "fuzz support: %s\n", message.c_str());
  std::_Exit(70);  // not a finding: libFuzzer sees an ordinary exit, not a crash
}

void RemoveScratchDir() {
  std::error_code ignored;
  fs::remove_all(ScratchDir(), ignored);
}

}  // namespace

void Initialize() {
  cv::utils::logging::setLogLevel(cv::utils::logging::LOG_LEVEL_SILENT);
  cv::setNumThreads(0);
  ScratchDir();
}

const std::string& ScratchDir() {
  // Never destroyed: the exit handler that removes the folder runs after static destructors.
  static const std::string* const dir = new std::string([] {
    std::error_code error;
    const fs::path base = fs::temp_directory_path(error);
    if (error) Stop("no temporary folder: " + error.message());
    const std::string pattern = (base / "attend-fuzz-XXXXXX").string();
    std::string name = pattern;
    if (mkdtemp(name.data()) == nullptr) Stop("cannot make a folder like " + pattern);
    std::atexit(RemoveScratchDir);
    return name;
  }());
  return *dir;
}

std::string ScratchPath(const std::string& name) {
  return (fs::path(ScratchDir()) / name).string();
}

std::string ScratchFile(const std::string& name, const std::string& bytes) {
  const std::string path = ScratchPath(name);
  WriteFile(path, bytes);
  return path;
}

void WriteFile(const std::string& path, const std::string& bytes) {
  std::error_code error;
  fs::create_directories(fs::path(path).parent_path(), error);
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  out.close();
  if (!out) Stop("cannot write " + path);
}

std::string ReadFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) Stop("cannot read " + path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

void ReportDocumentedError(const char* kind, const Error& error) {
  static const bool verbose = std::getenv("ATTEND_FUZZ_VERBOSE") != nullptr;
  if (verbose) std::fprintf(stderr, "%s: %s\n", kind, error.what());
}

void Fail(const std::string& message) {
  std::fprintf(stderr, "fuzz target: %s\n", message.c_str());
  std::fflush(stderr);
  std::abort();
}

}  // namespace attend::fuzz
