// Errors that reach the user, and the exit status each one maps to (SPEC 3.2).
#pragma once

#include <sstream>
#include <stdexcept>
#include <string>

namespace attend {

// Exit statuses of the `attend` program (SPEC 3.2).
enum class ExitStatus : int {
  kOk = 0,
  kInternal = 1,  // a bug: an internal invariant did not hold
  kUsage = 2,     // bad command line or configuration
  kBadInput = 3,  // bad input data: a missing, unreadable or inconsistent sequence or image
  kPlugin = 4,    // a feature plugin failed inside its own code (a Python plugin's exception)
};

// Base of every error that is reported to the user. The message says what and where
// (file, YAML key and line, frame index and path); it is printed as "attend: error: MESSAGE".
// A message longer than kMaxMessageBytes keeps its beginning and end, with the number of bytes
// left out between them: a value of 100 MB is never echoed whole.
inline constexpr size_t kMaxMessageBytes = 4096;

class Error : public std::runtime_error {
 public:
  Error(ExitStatus status, const std::string& message)
      : std::runtime_error(BoundedMessage(message)), status_(status) {}
  // `message` cut to at most about kMaxMessageBytes (see above).
  static std::string BoundedMessage(const std::string& message);
  ExitStatus status() const { return status_; }

 private:
  ExitStatus status_;
};

// Bad command line or configuration (exit status 2).
class ConfigError : public Error {
 public:
  explicit ConfigError(const std::string& message) : Error(ExitStatus::kUsage, message) {}
};

// An output location that cannot be used or written: a non-empty folder without --overwrite,
// a read-only folder, a full disk. A usage error (exit status 2): the user picks the output.
class OutputError : public Error {
 public:
  explicit OutputError(const std::string& message) : Error(ExitStatus::kUsage, message) {}
};

// Bad input data (exit status 3).
class InputError : public Error {
 public:
  explicit InputError(const std::string& message) : Error(ExitStatus::kBadInput, message) {}
};

// A feature plugin that failed inside its own code: a Python feature that raised (the message
// holds the feature's name and the Python traceback). Exit status 4.
class PluginError : public Error {
 public:
  explicit PluginError(const std::string& message) : Error(ExitStatus::kPlugin, message) {}
};

// A broken internal invariant (exit status 1).
class InternalError : public Error {
 public:
  explicit InternalError(const std::string& message) : Error(ExitStatus::kInternal, message) {}
};

namespace internal {
// Collects a message with operator<< and throws InternalError when destroyed.
class CheckFailure {
 public:
  CheckFailure(const char* file, int line, const char* condition);
  [[noreturn]] ~CheckFailure() noexcept(false);
  template <typename T>
  CheckFailure& operator<<(const T& value) {
    stream_ << value;
    return *this;
  }

 private:
  std::ostringstream stream_;
};
}  // namespace internal

}  // namespace attend

// Internal invariant: stops the program with exit status 1 when it does not hold.
// Usage: ATTEND_CHECK(a == b) << "context " << value;
#define ATTEND_CHECK(condition) \
  if (condition) {              \
  } else                        \
    ::attend::internal::CheckFailure(__FILE__, __LINE__, #condition)
