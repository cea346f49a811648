#include "tests/support/temp_dir.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <random>

namespace attend::testing {

TempDir::TempDir() {
  const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::string name = "attend-test";
  if (info != nullptr) name += std::string("-") + info->test_suite_name() + "-" + info->name();
  std::random_device random;
  path_ = std::filesystem::temp_directory_path() /
          (name + "-" + std::to_string(getpid()) + "-" + std::to_string(random() % 1000000));
  std::filesystem::create_directories(path_);
}

TempDir::~TempDir() {
  std::error_code ignored;
  std::filesystem::remove_all(path_, ignored);
}

std::string TempDir::File(const std::string& name) const { return (path_ / name).string(); }

std::string TempDir::Write(const std::string& name, const std::string& text) const {
  const std::filesystem::path file = path_ / name;
  std::filesystem::create_directories(file.parent_path());
  std::ofstream out(file);
  out << text;
  return file.string();
}

std::string ProjectRoot() {
  const char* home = std::getenv("ATTEND_HOME");
  return home != nullptr ? home : ATTEND_SOURCE_ROOT_FALLBACK;
}

std::string SharedData() {
  const char* data = std::getenv("ATTEND_SHARED_DATA");
  if (data != nullptr) return data;
  return (std::filesystem::path(ProjectRoot()) / ".." / "shared" / "data")
      .lexically_normal()
      .string();
}

}  // namespace attend::testing
