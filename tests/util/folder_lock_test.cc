#include "util/folder_lock.h"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "tests/support/error_message.h"
#include "tests/support/temp_dir.h"
#include "util/error.h"
#include "util/output_folder.h"

namespace fs = std::filesystem;

namespace attend {
namespace {

bool Has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(FolderLock, ASecondWriterIsRefusedNamingTheHolderUntilTheFirstReleases) {
  testing::TempDir dir;
  {
    FolderLock first(dir.path().string(), "run");
    EXPECT_TRUE(first.held());
    EXPECT_TRUE(first.stale_holder().empty());
    EXPECT_TRUE(fs::exists(dir.path() / FolderLock::kFileName));
    // A second lock, even in the same process, is another writer.
    const std::string message = testing::ErrorOf<OutputError>(
        [&] { FolderLock second(dir.path().string(), "run"); });
    EXPECT_TRUE(Has(message, dir.path().string() + ": in use by another attend run (pid " +
                                 std::to_string(getpid())))
        << message;
    EXPECT_TRUE(Has(FolderLockHolder(dir.path().string()), "pid " + std::to_string(getpid())));
    // Asked before the lock is taken, a writer is refused with the same message.
    EXPECT_EQ(testing::ErrorOf<OutputError>(
                  [&] { RefuseFolderInUse(dir.path().string(), "run"); }),
              message);
  }
  EXPECT_FALSE(fs::exists(dir.path() / FolderLock::kFileName));
  EXPECT_EQ(FolderLockHolder(dir.path().string()), "");
  EXPECT_NO_THROW(RefuseFolderInUse(dir.path().string(), "run"));
  EXPECT_NO_THROW(RefuseFolderInUse((dir.path() / "not-yet").string(), "run"));
  FolderLock again(dir.path().string(), "run");
  EXPECT_TRUE(again.held());
}

TEST(FolderLock, TheLockOfAProcessThatDiedIsTakenOverAndNamed) {
  testing::TempDir dir;
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    FolderLock held(dir.path().string(), "run");
    _exit(0);  // no destructor: the lock file stays, as after SIGKILL
  }
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  ASSERT_TRUE(fs::exists(dir.path() / FolderLock::kFileName));
  EXPECT_EQ(FolderLockHolder(dir.path().string()), "");  // stale: nobody holds it
  EXPECT_NO_THROW(RefuseFolderInUse(dir.path().string(), "run"));
  FolderLock taken(dir.path().string(), "run");
  EXPECT_TRUE(Has(taken.stale_holder(), "pid " + std::to_string(child))) << taken.stale_holder();
}

TEST(FolderLock, MovingKeepsOneHolder) {
  testing::TempDir dir;
  FolderLock first(dir.path().string(), "run");
  FolderLock moved = std::move(first);
  EXPECT_FALSE(first.held());  // NOLINT(bugprone-use-after-move): the moved-from state
  EXPECT_TRUE(moved.held());
  moved.Release();
  EXPECT_FALSE(fs::exists(dir.path() / FolderLock::kFileName));
}

TEST(FolderLock, AnUnwritableFolderIsAnOutputErrorNamingIt) {
  if (geteuid() == 0) GTEST_SKIP() << "root writes into a read-only folder";
  testing::TempDir dir;
  fs::permissions(dir.path(), fs::perms::owner_read | fs::perms::owner_exec);
  const std::string message =
      testing::ErrorOf<OutputError>([&] { FolderLock lock(dir.path().string(), "run"); });
  fs::permissions(dir.path(), fs::perms::owner_all);
  EXPECT_TRUE(Has(message, "cannot create the lock file")) << message;
}

OutputFolderRules RunRules() {
  OutputFolderRules rules;
  rules.what = "run";
  rules.own_entries = {"frames.jsonl"};
  rules.is_previous_output = [](const std::string& folder) {
    return fs::exists(fs::path(folder) / "frames.jsonl");
  };
  return rules;
}

TEST(PrepareOutputFolder, LocksTheFolderAndCountsAStaleLockFileAsNothing) {
  testing::TempDir dir;
  const std::string out = dir.File("run");
  {
    const FolderLock lock = PrepareOutputFolder(out, false, RunRules());
    EXPECT_TRUE(lock.held());
    std::ofstream(out + "/frames.jsonl") << "{}\n";
    const std::string message =
        testing::ErrorOf<OutputError>([&] { (void)PrepareOutputFolder(out, true, RunRules()); });
    EXPECT_TRUE(Has(message, "in use by another attend run")) << message;
    EXPECT_TRUE(fs::exists(out + "/frames.jsonl"));  // the first writer's file is untouched
  }
  // Only a lock file left by a killed writer: the folder counts as empty.
  fs::remove(out + "/frames.jsonl");
  std::ofstream(out + "/" + FolderLock::kFileName) << "pid 1 on nowhere\n";
  const FolderLock lock = PrepareOutputFolder(out, false, RunRules());
  EXPECT_EQ(lock.stale_holder(), "pid 1 on nowhere");
}

}  // namespace
}  // namespace attend
