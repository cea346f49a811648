// Runs the `attend` program from tests: stdout and stderr to files, exit status back.
#pragma once

#include <sys/types.h>

#include <string>
#include <vector>

#include "tests/support/temp_dir.h"

namespace attend::testing {

struct Result {
  int status = -1;  // exit status, or 128 + signal
  std::string out;
  std::string err;
};

// The whole text of a file ("" when it cannot be read).
std::string ReadText(const std::string& path);

// Starts `binary` with `args` in `dir`, stdout and stderr to dir/stdout and dir/stderr.
pid_t Start(const std::string& binary, const TempDir& dir, const std::vector<std::string>& args);

// Waits for `pid` and collects its result.
Result Wait(const TempDir& dir, pid_t pid);

// Start then Wait.
Result Run(const std::string& binary, const TempDir& dir, const std::vector<std::string>& args);

bool Contains(const std::string& text, const std::string& part);

}  // namespace attend::testing
