#include "util/file_checks.h"

#include <cerrno>
#include <cstring>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace attend {

namespace {

// "a folder", "a fifo", ... for a file type that is not a regular file.
std::string KindOf(mode_t mode) {
  if (S_ISDIR(mode)) return "a folder";
  if (S_ISFIFO(mode)) return "a fifo (named pipe)";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

std::string Prefix(const std::string& path, const std::string& what) {
  return path + ": " + (what.empty() ? std::string("the file") : what);
}

std::string Megabytes(std::uintmax_t bytes) {
  return std::to_string((bytes + (1u << 20) - 1) >> 20) + " MB";
}

void CheckStat(const struct stat& info, const std::string& path, const std::string& what,
               ExitStatus status, std::uintmax_t max_bytes) {
  if (!S_ISREG(info.st_mode)) {
    ThrowError(status, Prefix(path, what) + " is " + KindOf(info.st_mode) + ", not a file");
  }
  const auto size = static_cast<std::uintmax_t>(info.st_size);
  if (max_bytes > 0 && size > max_bytes) {
    ThrowError(status, Prefix(path, what) + " is " + std::to_string(size) + " bytes, more than " +
                           Megabytes(max_bytes) + " (docs/LIMITS.md)");
  }
}

[[noreturn]] void ThrowMissing(const std::string& path, const std::string& what, ExitStatus status,
                               int error_number) {
  if (path.empty()) ThrowError(status, (what.empty() ? "a file" : what) + " is an empty path");
  if (error_number == ENOENT || error_number == ENOTDIR) {
    ThrowError(status, Prefix(path, what) + " does not exist");
  }
  ThrowError(status, Prefix(path, what) + " cannot be read: " + std::strerror(error_number));
}

}  // namespace

void ThrowError(ExitStatus status, const std::string& message) {
  switch (status) {
    case ExitStatus::kUsage:
      throw ConfigError(message);
    case ExitStatus::kBadInput:
      throw InputError(message);
    case ExitStatus::kPlugin:
      throw PluginError(message);
    case ExitStatus::kOk:
    case ExitStatus::kInternal:
      break;
  }
  throw InternalError(message);
}

void RequireRegularFile(const std::string& path, const std::string& what, ExitStatus status,
                        std::uintmax_t max_bytes) {
  struct stat info {};
  if (path.empty() || ::stat(path.c_str(), &info) != 0) {
    ThrowMissing(path, what, status, path.empty() ? ENOENT : errno);
  }
  CheckStat(info, path, what, status, max_bytes);
}

std::string ReadRegularFile(const std::string& path, const std::string& what, ExitStatus status,
                            std::uintmax_t max_bytes) {
  if (path.empty()) ThrowMissing(path, what, status, ENOENT);
  // O_NONBLOCK: opening a fifo for reading would otherwise wait for a writer.
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) ThrowMissing(path, what, status, errno);
  struct FdCloser {
    int fd;
    ~FdCloser() { ::close(fd); }
  } closer{fd};
  struct stat info {};
  if (::fstat(fd, &info) != 0) ThrowMissing(path, what, status, errno);
  CheckStat(info, path, what, status, max_bytes);
  std::string text;
  text.resize(static_cast<size_t>(info.st_size));
  size_t done = 0;
  while (true) {
    if (done == text.size()) {
      // The file may have grown since fstat: read on, within the cap.
      const size_t grown = text.size() + 65536;
      if (max_bytes > 0 && done > max_bytes) {
        ThrowError(status, Prefix(path, what) + " grew past " + Megabytes(max_bytes) +
                               " while it was read (docs/LIMITS.md)");
      }
      text.resize(grown);
    }
    const ssize_t got = ::read(fd, text.data() + done, text.size() - done);
    if (got < 0) {
      if (errno == EINTR) continue;
      ThrowError(status, Prefix(path, what) + " cannot be read: " + std::strerror(errno));
    }
    if (got == 0) break;
    done += static_cast<size_t>(got);
  }
  text.resize(done);
  return text;
}

}  // namespace attend
