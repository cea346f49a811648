#include "util/folder_lock.h"

#include <cerrno>
#include <chrono>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <utility>

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include "util/error.h"

namespace fs = std::filesystem;

namespace attend {

namespace {

std::string HostName() {
  char name[256] = {};
  if (gethostname(name, sizeof(name) - 1) != 0) return "an unknown host";
  return name;
}

std::string UtcNow() {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char text[32];
  std::strftime(text, sizeof(text), "%Y-%m-%d %H:%M:%S UTC", &utc);
  return text;
}

// The program's command line, from /proc, cut to a readable length.
std::string CommandLine() {
  std::string text;
  const int fd = ::open("/proc/self/cmdline", O_RDONLY | O_CLOEXEC);
  if (fd >= 0) {
    char buffer[512];
    const ssize_t got = ::read(fd, buffer, sizeof(buffer));
    ::close(fd);
    for (ssize_t i = 0; i < got; ++i) text += buffer[i] == '\0' ? ' ' : buffer[i];
  }
  while (!text.empty() && text.back() == ' ') text.pop_back();
  if (text.size() >= 200) text = text.substr(0, 200) + "...";
  return text;
}

// The holder line stored in an open lock file, "" when it cannot be read.
std::string ReadHolder(int fd) {
  char buffer[1024];
  const ssize_t got = ::pread(fd, buffer, sizeof(buffer) - 1, 0);
  if (got <= 0) return "";
  std::string text(buffer, static_cast<size_t>(got));
  while (!text.empty() && (text.back() == '\n' || text.back() == '\0')) text.pop_back();
  for (char& c : text) {
    if (static_cast<unsigned char>(c) < 0x20) c = ' ';
  }
  return text;
}

// True when `fd` is still the file at `path` (not unlinked by a releasing holder meanwhile).
bool StillLinked(int fd, const std::string& path) {
  struct stat open_file {};
  struct stat named {};
  if (::fstat(fd, &open_file) != 0 || ::stat(path.c_str(), &named) != 0) return false;
  return open_file.st_dev == named.st_dev && open_file.st_ino == named.st_ino;
}

// The message of a folder locked by the live process `holder`.
std::string InUse(const std::string& folder, const std::string& what, const std::string& holder) {
  return folder + ": in use by another attend " + what + " (" + holder +
         "); wait until it ends, or write to another folder";
}

}  // namespace

FolderLock::FolderLock(const std::string& folder, const std::string& what)
    : path_((fs::path(folder) / kFileName).string()) {
  // A releasing holder unlinks the file: a lock taken on an unlinked file protects nothing,
  // so it is taken again on the new one.
  for (int attempt = 0; attempt < 100; ++attempt) {
    const int fd = ::open(path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0) {
      throw OutputError(folder + ": cannot create the lock file " + kFileName + ": " +
                        std::strerror(errno));
    }
    // A moment's retry: FolderLockHolder's probe (a status listing) holds a shared lock briefly.
    int locked = ::flock(fd, LOCK_EX | LOCK_NB);
    for (int retry = 0; locked != 0 && errno == EWOULDBLOCK && retry < 5; ++retry) {
      ::usleep(20000);
      locked = ::flock(fd, LOCK_EX | LOCK_NB);
    }
    if (locked != 0) {
      const int error_number = errno;
      const std::string holder = ReadHolder(fd);
      ::close(fd);
      if (error_number == EWOULDBLOCK) {
        throw OutputError(InUse(folder, what, holder.empty() ? "holder unknown" : holder));
      }
      throw OutputError(folder + ": cannot lock " + kFileName + ": " +
                        std::strerror(error_number));
    }
    if (!StillLinked(fd, path_)) {
      ::close(fd);
      continue;
    }
    stale_holder_ = ReadHolder(fd);
    const std::string line = "pid " + std::to_string(getpid()) + " on " + HostName() +
                             ", since " + UtcNow() + ", " + CommandLine() + "\n";
    if (::ftruncate(fd, 0) != 0 ||
        ::pwrite(fd, line.data(), line.size(), 0) != static_cast<ssize_t>(line.size())) {
      const int error_number = errno;
      ::close(fd);
      throw OutputError(path_ + ": cannot write the lock file: " + std::strerror(error_number));
    }
    fd_ = fd;
    return;
  }
  throw OutputError(folder + ": the lock file " + kFileName + " keeps being replaced; " +
                    "another program is locking the folder at the same time");
}

FolderLock::FolderLock(FolderLock&& other) noexcept
    : path_(std::move(other.path_)), fd_(std::exchange(other.fd_, -1)),
      stale_holder_(std::move(other.stale_holder_)) {}

FolderLock& FolderLock::operator=(FolderLock&& other) noexcept {
  if (this != &other) {
    Release();
    path_ = std::move(other.path_);
    fd_ = std::exchange(other.fd_, -1);
    stale_holder_ = std::move(other.stale_holder_);
  }
  return *this;
}

FolderLock::~FolderLock() { Release(); }

void FolderLock::Release() {
  if (fd_ < 0) return;
  // Unlinked before it is unlocked: a waiting process that then gets the lock sees the file
  // is gone and takes a new one.
  ::unlink(path_.c_str());
  ::close(fd_);
  fd_ = -1;
}

void RefuseFolderInUse(const std::string& folder, const std::string& what) {
  const std::string holder = FolderLockHolder(folder);
  if (!holder.empty()) throw OutputError(InUse(folder, what, holder));
}

std::string FolderLockHolder(const std::string& folder) {
  const std::string path = (fs::path(folder) / FolderLock::kFileName).string();
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return "";
  std::string holder;
  if (::flock(fd, LOCK_SH | LOCK_NB) != 0 && errno == EWOULDBLOCK) {
    holder = ReadHolder(fd);
    if (holder.empty()) holder = "holder unknown";
  }
  ::close(fd);
  return holder;
}

}  // namespace attend
