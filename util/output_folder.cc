#include "util/output_folder.h"

#include <sstream>

#include <fstream>
#include <iostream>

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include <filesystem>

#include "util/error.h"

namespace fs = std::filesystem;

namespace attend {

namespace {

// True when `folder` holds nothing but, possibly, its lock file.
bool OnlyTheLock(const std::string& folder, std::error_code& error) {
  for (fs::directory_iterator it(folder, error), end; !error && it != end; it.increment(error)) {
    if (it->path().filename() != FolderLock::kFileName) return false;
  }
  return true;
}

}  // namespace

FolderLock PrepareOutputFolder(const std::string& folder, bool overwrite,
                               const OutputFolderRules& rules) {
  if (folder.empty()) throw OutputError("the output folder is an empty path");
  std::error_code error;
  const bool exists = fs::exists(folder, error);
  if (error) throw OutputError(folder + ": cannot inspect the output folder: " + error.message());
  if (exists && !fs::is_directory(folder, error)) {
    throw OutputError(folder + ": the output path exists and is not a folder");
  }
  fs::create_directories(folder, error);
  if (error) throw OutputError(folder + ": cannot create the output folder: " + error.message());
  FolderLock lock;
  if (rules.lock) {
    lock = FolderLock(folder, rules.what);
    if (!lock.stale_holder().empty()) {
      std::cerr << "attend: note: " << folder << ": took over the lock of an earlier " << rules.what
                << " that ended without releasing it (" << lock.stale_holder() << ")\n";
    }
  }
  const bool empty = OnlyTheLock(folder, error);
  if (error) throw OutputError(folder + ": cannot read the output folder: " + error.message());
  if (!empty) {
    if (!overwrite) {
      throw OutputError(folder + ": the output folder is not empty (--overwrite replaces a " +
                        "previous " + rules.what + " there)");
    }
    if (!rules.is_previous_output(folder)) {
      throw OutputError(folder + ": --overwrite refused: the folder is not empty and does not " +
                        "hold a previous " + rules.what + " of attend; choose another folder");
    }
    for (const std::string& entry : rules.own_entries) {
      const fs::path path = fs::path(folder) / entry;
      fs::remove_all(path, error);
      if (error) {
        throw OutputError(path.string() + ": cannot remove it to overwrite the " + rules.what +
                          ": " + error.message());
      }
    }
  }
  return lock;
}

void ReplaceFile(const std::string& path, const std::string& what,
                 const std::function<bool(const std::string& temporary)>& write) {
  const fs::path target(path);
  std::string name = ".";
  name += target.filename().string();
  name += ".tmp-";
  name += std::to_string(getpid());
  const fs::path temporary = target.parent_path() / name;
  const auto fail = [&](const std::string& reason) {
    std::error_code ignored;
    fs::remove(temporary, ignored);
    throw OutputError(path + ": cannot write" + (what.empty() ? "" : " " + what) +
                      (reason.empty() ? "" : " (" + reason + ")"));
  };
  bool written = false;
  try {
    written = write(temporary.string());
  } catch (const Error& e) {
    fail(e.what());
  }
  if (!written) fail("");
  std::error_code error;
  fs::rename(temporary, target, error);
  if (error) fail(error.message());
}

namespace {

// The system's reason for `error_number`, naming a full disk as such.
std::string ErrnoText(int error_number) {
  if (error_number == ENOSPC || error_number == EDQUOT) {
    return std::string("the disk is full: ") + std::strerror(error_number);
  }
  return std::strerror(error_number);
}

}  // namespace

void ReplaceFileText(const std::string& path, const std::string& text, const std::string& what) {
  // Written with write(2), so that the reason of a failure (a full disk, a folder made
  // read-only) reaches the message, which an ofstream loses.
  ReplaceFile(path, what, [&](const std::string& temporary) {
    const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd < 0) throw OutputError(ErrnoText(errno));
    std::size_t done = 0;
    while (done < text.size()) {
      const ssize_t wrote = ::write(fd, text.data() + done, text.size() - done);
      if (wrote < 0 && errno == EINTR) continue;
      if (wrote <= 0) {
        const int error_number = wrote < 0 ? errno : ENOSPC;
        ::close(fd);
        throw OutputError(ErrnoText(error_number));
      }
      done += static_cast<std::size_t>(wrote);
    }
    if (::close(fd) != 0) throw OutputError(ErrnoText(errno));
    return true;
  });
}

std::string ReadFileText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace attend
