#include "util/error.h"

#include <gtest/gtest.h>

namespace attend {
namespace {

TEST(Error, EachKindCarriesItsExitStatus) {
  EXPECT_EQ(ConfigError("x").status(), ExitStatus::kUsage);
  EXPECT_EQ(InputError("x").status(), ExitStatus::kBadInput);
  EXPECT_EQ(InternalError("x").status(), ExitStatus::kInternal);
  EXPECT_EQ(static_cast<int>(ExitStatus::kUsage), 2);
  EXPECT_EQ(static_cast<int>(ExitStatus::kBadInput), 3);
}

TEST(Error, CheckThrowsInternalErrorWithContextOnlyWhenFalse) {
  EXPECT_NO_THROW(ATTEND_CHECK(1 + 1 == 2) << "never");
  try {
    const int level = 7;
    ATTEND_CHECK(level < 3) << "level " << level;
    FAIL() << "ATTEND_CHECK did not throw";
  } catch (const InternalError& e) {
    EXPECT_NE(std::string(e.what()).find("level < 3"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("level 7"), std::string::npos);
  }
}

TEST(Error, AHugeMessageKeepsItsEndsAndSaysHowMuchWasLeftOut) {
  const std::string value(100000, 'x');
  const ConfigError error("cfg.yaml:3: threads: expected an integer, got '" + value + "' (end)");
  const std::string message = error.what();
  EXPECT_LE(message.size(), kMaxMessageBytes + 64);
  EXPECT_EQ(message.rfind("cfg.yaml:3: threads: expected an integer, got 'xxx", 0), 0u);
  EXPECT_NE(message.find("bytes left out"), std::string::npos);
  EXPECT_EQ(message.substr(message.size() - 7), "' (end)");
  EXPECT_EQ(ConfigError("short").what(), std::string("short"));
}

}  // namespace
}  // namespace attend
