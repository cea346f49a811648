// The message of the error a piece of code throws, for tests that check what a message names.
#pragma once

#include <string>

#include "util/error.h"

namespace attend::testing {

// Runs `body` and returns the message of the exception of type E it throws; "" when it throws
// none. Other exceptions propagate and fail the test.
template <typename E, typename Body>
std::string ErrorOf(Body body) {
  try {
    body();
  } catch (const E& e) {
    return e.what();
  }
  return "";
}

template <typename Body>
std::string ConfigErrorOf(Body body) {
  return ErrorOf<ConfigError>(body);
}

template <typename Body>
std::string InputErrorOf(Body body) {
  return ErrorOf<InputError>(body);
}

}  // namespace attend::testing
