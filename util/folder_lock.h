// One writer a folder: a run folder or a sweep cell is locked while a process writes it, so
// that a second `attend run --out X --overwrite` (or a second sweep on the same cell) is
// refused instead of mixing its files with the first's. The lock is the file FOLDER/.attend-lock
// held with an exclusive flock(2): the kernel releases it when its process ends in any way, so
// a lock left by a killed run is recognised as stale and taken over.
#pragma once

#include <string>

namespace attend {

class FolderLock {
 public:
  // The name of the lock file inside a locked folder.
  static constexpr const char* kFileName = ".attend-lock";

  FolderLock() = default;
  // Locks `folder`, which must exist, for `what` ("run", "sweep cell": for the holder's line
  // and messages). Throws OutputError "FOLDER: in use by another attend WHAT (pid P on HOST,
  // since TIME, COMMAND); ..." while another process holds it. A lock file whose process has
  // ended is taken over: stale_holder() then describes the process that left it.
  FolderLock(const std::string& folder, const std::string& what);
  FolderLock(FolderLock&& other) noexcept;
  FolderLock& operator=(FolderLock&& other) noexcept;
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;
  // Releases the lock and removes the lock file.
  ~FolderLock();

  bool held() const { return fd_ >= 0; }
  // "pid P on HOST, since TIME, COMMAND" of the ended process whose lock was taken over, or "".
  const std::string& stale_holder() const { return stale_holder_; }
  // Releases early (the destructor then does nothing).
  void Release();

 private:
  std::string path_;
  int fd_ = -1;
  std::string stale_holder_;
};

// The holder line of a locked folder ("pid P on HOST, since TIME, COMMAND") when another live
// process holds its lock, "" when it is free or the lock is stale. For status listings.
std::string FolderLockHolder(const std::string& folder);

// The OutputError a FolderLock of `folder` would throw now, when another live process holds it;
// nothing otherwise. For a command that works a while before it writes (a live run warms up):
// it refuses a folder in use at once. The lock itself is still taken later.
void RefuseFolderInUse(const std::string& folder, const std::string& what);

}  // namespace attend
