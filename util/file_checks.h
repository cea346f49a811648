// Reading a file that the user names: it must be a regular file, and files read whole are
// capped in size (docs/LIMITS.md), so that a folder, a fifo or /dev/zero given as a
// configuration is refused at once, by name, instead of being read for minutes or as "missing".
#pragma once

#include <cstdint>
#include <string>

#include "util/error.h"

namespace attend {

// Sizes of the files read whole as text (docs/LIMITS.md).
inline constexpr std::uintmax_t kMaxConfigBytes = 16u << 20;  // YAML: configurations, sweeps
inline constexpr std::uintmax_t kMaxTextBytes = 256u << 20;   // skin samples, records

// Throws an Error of `status` ("PATH: WHAT is a folder, not a file"; "... is a fifo ...";
// "... does not exist") unless `path`, symbolic links followed, is an existing regular file.
// With `max_bytes` > 0, a larger file is refused naming its size and the cap.
void RequireRegularFile(const std::string& path, const std::string& what, ExitStatus status,
                        std::uintmax_t max_bytes = 0);

// The content of the regular file `path`, at most `max_bytes` long: RequireRegularFile's
// refusals, checked on the opened file (so that it cannot be swapped between check and read),
// and a read error named as such. A fifo is never waited on.
std::string ReadRegularFile(const std::string& path, const std::string& what, ExitStatus status,
                            std::uintmax_t max_bytes);

// Throws the attend Error class of `status` (ConfigError, InputError, PluginError, ...).
[[noreturn]] void ThrowError(ExitStatus status, const std::string& message);

}  // namespace attend
