// Running the `attend` binary that this test target was built with (ATTEND_BINARY).
#pragma once

#include <string>
#include <vector>

#include "tests/support/attend_process.h"
#include "tests/support/temp_dir.h"

namespace attend::testing {

inline pid_t StartAttend(const TempDir& dir, const std::vector<std::string>& args) {
  return Start(ATTEND_BINARY, dir, args);
}

inline Result Attend(const TempDir& dir, const std::vector<std::string>& args) {
  return Run(ATTEND_BINARY, dir, args);
}

}  // namespace attend::testing
