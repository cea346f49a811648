#include "util/file_checks.h"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <chrono>
#include <filesystem>

#include "tests/support/error_message.h"
#include "tests/support/temp_dir.h"

namespace fs = std::filesystem;

namespace attend {
namespace {

bool HasText(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(FileChecks, ARegularFileIsReadWhole) {
  testing::TempDir dir;
  const std::string path = dir.Write("a.yaml", "a: 1\n");
  EXPECT_EQ(ReadRegularFile(path, "the configuration", ExitStatus::kUsage, 100), "a: 1\n");
  EXPECT_NO_THROW(RequireRegularFile(path, "", ExitStatus::kUsage, 5));
}

TEST(FileChecks, EachKindOfNonFileIsNamedWithTheGivenStatus) {
  testing::TempDir dir;
  const std::string fifo = dir.File("pipe");
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  const auto config_error = [](const std::string& path) {
    return testing::ErrorOf<ConfigError>(
        [&] { ReadRegularFile(path, "the configuration", ExitStatus::kUsage, 1000); });
  };
  const auto start = std::chrono::steady_clock::now();
  EXPECT_EQ(config_error(fifo), fifo + ": the configuration is a fifo (named pipe), not a file");
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(2));  // not waited on
  EXPECT_EQ(config_error("/dev/zero"), "/dev/zero: the configuration is a character device, not a file");
  EXPECT_EQ(config_error(dir.path().string()),
            dir.path().string() + ": the configuration is a folder, not a file");
  EXPECT_EQ(config_error(dir.File("none.yaml")),
            dir.File("none.yaml") + ": the configuration does not exist");
  EXPECT_EQ(config_error(""), "the configuration is an empty path");
  const std::string input = testing::InputErrorOf(
      [&] { RequireRegularFile("/dev/null", "the skin model", ExitStatus::kBadInput); });
  EXPECT_TRUE(HasText(input, "/dev/null: the skin model is a character device")) << input;
}

TEST(FileChecks, AFileOverTheCapIsRefusedWithItsSize) {
  testing::TempDir dir;
  const std::string path = dir.Write("big.yaml", std::string(2000, 'a'));
  const std::string message = testing::ConfigErrorOf(
      [&] { ReadRegularFile(path, "the configuration", ExitStatus::kUsage, 1000); });
  EXPECT_TRUE(HasText(message, "is 2000 bytes, more than 1 MB (docs/LIMITS.md)")) << message;
  EXPECT_TRUE(testing::ConfigErrorOf([&] { RequireRegularFile(path, "", ExitStatus::kUsage, 1999); })
                  .size() > 0);
}

}  // namespace
}  // namespace attend
