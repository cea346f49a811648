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

}  // namespace
}  // namespace attend
