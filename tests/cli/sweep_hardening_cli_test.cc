// attend sweep against concurrent writers and a folder that changes under it (issue 46): a
// second runner of a cell, a second sweep, --extend and --collect while a sweep runs, a stale
// lock of a killed cell, a cell folder removed or made unwritable while the sweep runs, and a
// full disk. Each is a clear refusal or a cell recorded with its true reason, and the rest of
// the sweep is kept and collectable.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/mount.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "tests/cli/attend_cli.h"
#include "tests/cli/sweep_support.h"
#include "tests/support/attend_process.h"
#include "tests/support/temp_dir.h"

namespace fs = std::filesystem;

namespace attend {
namespace {

using testing::Attend;
using testing::Contains;
using testing::ReadText;
using testing::Result;
using testing::TempDir;

class SweepHardening : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new TempDir();
    testing::RenderSweepScenes(*dir_);
    // 60 frames: a cell runs for about two seconds, long enough to act on while it runs.
    const std::string scene = (fs::path(testing::ProjectRoot()) / "sequences" / "lab.yaml").string();
    const Result r = Attend(*dir_, {"synth", scene, "--out", "long", "--frames", "60", "--quiet"});
    ASSERT_EQ(r.status, 0) << r.err;
  }
  static void TearDownTestSuite() {
    delete dir_;
    dir_ = nullptr;
  }
  static std::string Scene(const std::string& name) { return dir_->File(name); }

  // Two cells over the long scene, one at a time.
  static std::string TwoSlowCells(const TempDir& work) {
    return work.Write("sweep.yaml", "set: {threads: 1}\ngrid:\n  select.max_new: [1, 2]\n"
                                    "inputs:\n  - sequence: " + Scene("long") + "\n");
  }

  static TempDir* dir_;
};

TempDir* SweepHardening::dir_ = nullptr;

// The folder of cell `index` once the sweep folder lists it.
std::string CellFolder(const std::string& sweep, int index) {
  const nlohmann::json json = nlohmann::json::parse(ReadText(sweep + "/sweep.json"));
  return sweep + "/cells/" + json["cells"][index]["name"].get<std::string>();
}

// Waits until `path` holds `text` (a status.json saying running); false after 60 s.
bool WaitFor(const std::string& path, const std::string& text) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (std::chrono::steady_clock::now() < deadline) {
    if (Contains(ReadText(path), text)) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return false;
}

bool WaitGone(const std::string& path) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (fs::exists(path)) {
    if (std::chrono::steady_clock::now() > deadline) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return true;
}

// Prepares a sweep folder without running a cell: a Slurm submission without sbatch.
void PrepareOnly(const TempDir& work, const std::string& file, const std::string& out) {
  const std::string path = std::getenv("PATH") != nullptr ? std::getenv("PATH") : "";
  setenv("PATH", work.File("nothing").c_str(), 1);
  const Result r = Attend(work, {"sweep", file, "--out", out, "--slurm"});
  setenv("PATH", path.c_str(), 1);
  ASSERT_EQ(r.status, 3) << r.err;
  ASSERT_TRUE(fs::exists(out + "/sweep.json"));
}

TEST_F(SweepHardening, WhileASweepRunsASecondRunnerOfItsCellOrItsFolderIsRefused) {
  const TempDir background;
  const TempDir work;
  const std::string file = TwoSlowCells(work);
  const std::string sweep = work.File("s");
  const pid_t pid =
      testing::StartAttend(background, {"sweep", file, "--out", sweep, "--local", "1"});
  ASSERT_TRUE(WaitFor(sweep + "/sweep.json", "\"cells\""));
  const std::string cell = CellFolder(sweep, 0);
  ASSERT_TRUE(WaitFor(cell + "/status.json", "\"running\""));

  // The same cell by hand: refused, naming the folder and who runs it.
  Result r = Attend(work, {"sweep", sweep, "--cell", "0"});
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_TRUE(Contains(r.err, cell + ": in use by another attend sweep cell (pid ")) << r.err;
  // A second sweep, an --extend, a --retry-failed: refused before anything is written.
  const std::string before = ReadText(sweep + "/sweep.json");
  for (const std::vector<std::string>& words :
       {std::vector<std::string>{"sweep", file, "--out", sweep},
        std::vector<std::string>{"sweep", file, "--out", sweep, "--extend"},
        std::vector<std::string>{"sweep", sweep, "--retry-failed"}}) {
    r = Attend(work, words);
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_TRUE(Contains(r.err, ": in use by another attend sweep (pid ")) << r.err;
  }
  EXPECT_EQ(ReadText(sweep + "/sweep.json"), before);
  // --status and --collect read: the cell is running.
  r = Attend(work, {"sweep", sweep, "--status"});
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(Contains(r.out, "running  pid ")) << r.out;
  r = Attend(work, {"sweep", sweep, "--collect"});
  EXPECT_EQ(r.status, 0) << r.err;

  const Result ended = testing::Wait(background, pid);
  EXPECT_EQ(ended.status, 0) << ended.err;
  EXPECT_TRUE(Contains(ended.out, "2 of 2 cells done, 0 failed")) << ended.out;
  EXPECT_FALSE(fs::exists(cell + "/.attend-lock"));
  EXPECT_FALSE(fs::exists(sweep + "/.attend-lock"));
}

TEST_F(SweepHardening, ASweepLeavesACellThatAnotherProcessRunsToIt) {
  const TempDir background;
  const TempDir work;
  const std::string sweep = work.File("s");
  PrepareOnly(work, TwoSlowCells(work), sweep);
  const std::string cell = CellFolder(sweep, 0);
  const pid_t pid = testing::StartAttend(background, {"sweep", sweep, "--cell", "0"});
  ASSERT_TRUE(WaitFor(cell + "/status.json", "\"running\""));
  const std::string started = nlohmann::json::parse(ReadText(cell + "/status.json"))["started"];
  const Result r = Attend(work, {"sweep", sweep, "--local", "2"});
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(Contains(r.out, "1 of 1 cells done")) << r.out;
  EXPECT_TRUE(Contains(r.out, "1 cells were left to another process that runs them")) << r.out;
  const Result ended = testing::Wait(background, pid);
  EXPECT_EQ(ended.status, 0) << ended.err;
  // Run once, by the process that started it.
  const nlohmann::json status = nlohmann::json::parse(ReadText(cell + "/status.json"));
  EXPECT_EQ(status["started"], started);
  EXPECT_EQ(status["state"], "done");
}

TEST_F(SweepHardening, TheLockOfAKilledCellIsTakenOverWhenTheSweepResumes) {
  const TempDir background;
  const TempDir work;
  const std::string sweep = work.File("s");
  PrepareOnly(work, TwoSlowCells(work), sweep);
  const std::string cell = CellFolder(sweep, 0);
  const pid_t pid = testing::StartAttend(background, {"sweep", sweep, "--cell", "0"});
  ASSERT_TRUE(WaitFor(cell + "/out/frames.jsonl", "\"frame\""));
  kill(pid, SIGKILL);
  testing::Wait(background, pid);
  ASSERT_TRUE(fs::exists(cell + "/.attend-lock"));  // left by the killed process
  // Its command goes on alone until it ends; then the cell is free.
  ASSERT_TRUE(WaitGone(cell + "/out/.attend-lock"));

  Result r = Attend(work, {"sweep", sweep, "--status"});
  EXPECT_TRUE(Contains(r.out, "2 waiting")) << r.out;
  r = Attend(work, {"sweep", sweep, "--local", "1"});
  ASSERT_EQ(r.status, 0) << r.err << ReadText(cell + "/status.json");
  EXPECT_TRUE(Contains(r.out, "2 of 2 cells done")) << r.out;
  const nlohmann::json status = nlohmann::json::parse(ReadText(cell + "/status.json"));
  EXPECT_TRUE(Contains(status.value("took_over_lock_of", ""), "pid " + std::to_string(pid)))
      << status.dump();
}

TEST_F(SweepHardening, ACellFolderRemovedWhileItRunsIsRecordedAndRunAgain) {
  const TempDir background;
  const TempDir work;
  const std::string file = TwoSlowCells(work);
  const std::string sweep = work.File("s");
  const pid_t pid =
      testing::StartAttend(background, {"sweep", file, "--out", sweep, "--local", "1"});
  ASSERT_TRUE(WaitFor(sweep + "/sweep.json", "\"cells\""));
  const std::string cell = CellFolder(sweep, 0);
  ASSERT_TRUE(WaitFor(cell + "/out/frames.jsonl", "\"frame\""));
  for (int tries = 0; tries < 100 && fs::exists(cell + "/cell.json"); ++tries) {
    std::error_code ignored;
    fs::remove_all(cell, ignored);  // the run may add a file meanwhile
  }
  const Result ended = testing::Wait(background, pid);
  EXPECT_EQ(ended.status, 3) << ended.out << ended.err;
  EXPECT_TRUE(Contains(ended.out, "1 of 2 cells done, 1 failed")) << ended.out;

  // The true reason; the other cell is kept and collected.
  Result r = Attend(work, {"sweep", sweep, "--status"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(Contains(r.out, "failed   exit status 2: the cell folder vanished while it ran"))
      << r.out;
  EXPECT_FALSE(Contains(r.out, "cannot start")) << r.out;
  r = Attend(work, {"sweep", sweep, "--collect"});
  ASSERT_EQ(r.status, 0) << r.err;
  const auto rows = testing::ReadCsv(sweep + "/sweep.csv");
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].at("state"), "failed");
  EXPECT_EQ(rows[1].at("state"), "done");
  EXPECT_NE(rows[1].at("coverage"), "");

  // Resume writes the folder again; --retry-failed runs the cell.
  r = Attend(work, {"sweep", sweep});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(Contains(r.err, "1 cell folders were missing or had no cell.json")) << r.err;
  EXPECT_TRUE(fs::exists(cell + "/cell.json"));
  r = Attend(work, {"sweep", sweep, "--retry-failed"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(testing::DoneCells(sweep).size(), 2u);

  // A done cell's folder removed by hand: the same command runs it again.
  fs::remove_all(CellFolder(sweep, 1));
  r = Attend(work, {"sweep", file, "--out", sweep});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(Contains(r.out, "1 of 1 cells done")) << r.out;
  EXPECT_EQ(testing::DoneCells(sweep).size(), 2u);
}

// A read-only cell folder: a read-only bind mount as root (root writes through permissions),
// else the folder's write permission taken away. Returns how to undo it; "" when it cannot.
struct ReadOnlyFolder {
  std::string path;
  bool mounted = false;
  bool Make(const std::string& folder) {
    path = folder;
    if (geteuid() != 0) return chmod(folder.c_str(), 0555) == 0;
    if (mount(folder.c_str(), folder.c_str(), nullptr, MS_BIND, nullptr) != 0) return false;
    mounted = true;
    return mount(nullptr, folder.c_str(), nullptr, MS_REMOUNT | MS_BIND | MS_RDONLY, nullptr) == 0;
  }
  void Undo() {
    if (mounted) umount(path.c_str());
    mounted = false;
    if (!path.empty()) chmod(path.c_str(), 0755);
  }
  ~ReadOnlyFolder() { Undo(); }
};

TEST_F(SweepHardening, AnUnwritableCellFolderFailsAloneWithItsReason) {
  const TempDir work;
  const std::string file = TwoSlowCells(work);
  const std::string sweep = work.File("s");
  PrepareOnly(work, file, sweep);
  const std::string cell = CellFolder(sweep, 0);
  ReadOnlyFolder read_only;
  if (!read_only.Make(cell)) GTEST_SKIP() << "cannot make a folder read-only here";

  Result r = Attend(work, {"sweep", sweep, "--local", "1"});
  EXPECT_EQ(r.status, 3) << r.out << r.err;
  EXPECT_TRUE(Contains(r.out, "1 of 2 cells done, 1 failed")) << r.out;
  EXPECT_TRUE(Contains(r.err, "cell 0 (")) << r.err;
  EXPECT_TRUE(Contains(r.err, cell + "/logs: cannot create the folder: ")) << r.err;
  EXPECT_FALSE(Contains(r.err, "cannot start")) << r.err;
  r = Attend(work, {"sweep", sweep, "--status"});
  EXPECT_TRUE(Contains(r.out, "failed   " + cell + ": cannot be written (")) << r.out;
  r = Attend(work, {"sweep", sweep, "--collect"});
  EXPECT_EQ(r.status, 0) << r.err;

  read_only.Undo();
  r = Attend(work, {"sweep", sweep, "--local", "1"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(Contains(r.out, "1 of 1 cells done, 0 failed")) << r.out;
}

// A full disk while the folder is prepared (a 64 KB tmpfs, mounted when the test may): the
// same command is then refused for the disk, not as "not a sweep folder", and once there is
// room it resumes and runs every cell.
TEST_F(SweepHardening, AFullDiskLeavesAFolderTheSameCommandResumes) {
  const TempDir work;
  const std::string disk = work.File("disk");
  fs::create_directories(disk);
  if (mount("tmpfs", disk.c_str(), "tmpfs", 0, "size=64k") != 0) {
    GTEST_SKIP() << "cannot mount a tmpfs here (needs root)";
  }
  struct Unmount {
    std::string path;
    ~Unmount() { umount(path.c_str()); }
  } unmount{disk};
  std::string values;
  for (int i = 1; i <= 20; ++i) values += (i > 1 ? ", " : "") + std::to_string(i);
  const std::string file =
      work.Write("sweep.yaml", "set: {threads: 1}\ngrid:\n  select.max_new: [" + values +
                                   "]\ninputs:\n  - sequence: " + Scene("lab") + "\n");
  const std::string sweep = disk + "/s";
  Result r = Attend(work, {"sweep", file, "--out", sweep, "--local", "2"});
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_TRUE(Contains(r.err, "the disk is full")) << r.err;
  r = Attend(work, {"sweep", file, "--out", sweep, "--local", "2"});
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_TRUE(Contains(r.err, "the disk is full")) << r.err;
  EXPECT_FALSE(Contains(r.err, "not a sweep folder")) << r.err;

  ASSERT_EQ(mount(nullptr, disk.c_str(), nullptr, MS_REMOUNT, "size=64m"), 0);
  r = Attend(work, {"sweep", file, "--out", sweep, "--local", "2"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(testing::DoneCells(sweep).size(), 20u);
  for (const auto& entry : fs::recursive_directory_iterator(sweep)) {
    EXPECT_EQ(entry.path().string().find(".tmp-"), std::string::npos) << entry.path();
  }
}

}  // namespace
}  // namespace attend
