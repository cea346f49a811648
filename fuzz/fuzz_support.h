// What every fuzz target shares (docs/FUZZING.md): a scratch folder of its own, the input as a
// file for the parsers that only take a path, and the rule that decides what is a finding.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "util/error.h"

namespace attend::fuzz {

// Once per process, from LLVMFuzzerInitialize: silences OpenCV's log and runs OpenCV on this
// thread only, so that every finding has one stack and the leak check sees every allocation.
void Initialize();

// A folder of this process's own below the temporary folder ($TMPDIR, which scripts/fuzz.sh
// points into build-fuzz/), made on first use and removed at a normal exit.
const std::string& ScratchDir();
// ScratchDir()/name. The same name gives the same path for the whole process.
std::string ScratchPath(const std::string& name);

// Replaces `path` with the bytes, creating the folders above it. A file that cannot be written
// is a problem of the machine, not a finding: it stops the process with a message.
void WriteFile(const std::string& path, const std::string& bytes);
// Writes a fixed file `name` with `bytes` in the scratch folder and returns its path.
std::string ScratchFile(const std::string& name, const std::string& bytes);
std::string ReadFile(const std::string& path);

inline std::string ToString(const uint8_t* data, size_t size) {
  return std::string(reinterpret_cast<const char*>(data), size);
}

// Prints "KIND: message" when ATTEND_FUZZ_VERBOSE is set.
void ReportDocumentedError(const char* kind, const Error& error);

// Runs `parse` and swallows the errors `attend` documents for bad input (util/error.h:
// ConfigError and OutputError, exit status 2; InputError, exit status 3). Everything else
// escapes on purpose: InternalError (a broken invariant, exit status 1), std::bad_alloc, a
// nlohmann or yaml-cpp exception, ... reach std::terminate with the throwing frame still on the
// stack, and libFuzzer saves the input with that stack.
// With ATTEND_FUZZ_VERBOSE set in the environment, the swallowed errors are printed (to check
// that a seed reads, or why it does not).
template <typename Function>
void ExpectOnlyDocumentedErrors(Function&& parse) {
  try {
    parse();
  } catch (const ConfigError& e) {
    ReportDocumentedError("ConfigError", e);
  } catch (const InputError& e) {
    ReportDocumentedError("InputError", e);
  } catch (const OutputError& e) {
    ReportDocumentedError("OutputError", e);
  }
}

// A property the target checks did not hold (a round trip that changes the data): prints the
// message and aborts, so that libFuzzer saves the input as a crash.
[[noreturn]] void Fail(const std::string& message);

}  // namespace attend::fuzz
