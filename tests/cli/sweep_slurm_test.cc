// attend sweep --slurm against a real one-node Slurm cluster, started for these tests by
// scripts/slurm_local.sh (Debian's slurm-wlm and munge; docs/SWEEPS.md): the same 2 x 2 grid as
// on this machine gives the same records and scores; sbatch refusing a job is exit 3 with its
// message; a cell the scheduler stops is reported as killed, with Slurm's word, not as done.
// Where the cluster cannot start, the tests skip and say why.
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
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

std::string Trimmed(std::string text) {
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
  return text;
}

class SweepSlurm : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new TempDir();
    state_ = dir_->File("slurm");
    script_ = (fs::path(testing::ProjectRoot()) / "scripts" / "slurm_local.sh").string();
    const Result started = testing::Run("/bin/bash", *dir_, {script_, "start", state_});
    if (started.status != 0) {
      skip_ = "a one-node Slurm cluster cannot start here (scripts/slurm_local.sh start: exit " +
              std::to_string(started.status) + "): " + Trimmed(started.err);
      return;
    }
    // The client's environment: SLURM_CONF, from the env file the script wrote.
    std::istringstream env(ReadText(state_ + "/env"));
    std::string line;
    while (std::getline(env, line)) {
      if (line.rfind("export ", 0) != 0) continue;
      const std::size_t equals = line.find('=');
      if (equals == std::string::npos) continue;
      std::string value = line.substr(equals + 1);
      if (value.size() >= 2 && (value.front() == '"' || value.front() == '\'')) {
        value = value.substr(1, value.size() - 2);
      }
      setenv(line.substr(7, equals - 7).c_str(), value.c_str(), 1);
    }
    testing::RenderSweepScenes(*dir_);
  }
  static void TearDownTestSuite() {
    if (skip_.empty()) testing::Run("/bin/bash", *dir_, {script_, "stop", state_});
    delete dir_;
    dir_ = nullptr;
  }
  void SetUp() override {
    if (!skip_.empty()) GTEST_SKIP() << skip_;
  }

  static std::string Scene(const std::string& name) { return dir_->File(name); }

  // Polls --status until no cell is running or waiting (and, when given, the text holds
  // `until`); returns the last status text.
  static std::string WaitForSweep(const TempDir& work, const std::string& sweep, int seconds,
                                  const std::string& until = "") {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(seconds);
    std::string text;
    while (std::chrono::steady_clock::now() < deadline) {
      const Result r = Attend(work, {"sweep", sweep, "--status"});
      text = r.out + r.err;
      if (r.status == 0 && Contains(r.out, " 0 running,") && Contains(r.out, " 0 waiting") &&
          Contains(r.out, until)) {
        break;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(500));
    }
    return text;
  }

  static TempDir* dir_;
  static std::string state_;
  static std::string script_;
  static std::string skip_;
};

TempDir* SweepSlurm::dir_ = nullptr;
std::string SweepSlurm::state_;
std::string SweepSlurm::script_;
std::string SweepSlurm::skip_;

// frames.jsonl without the timings, which differ between any two runs.
std::vector<nlohmann::json> Records(const std::string& run) {
  std::vector<nlohmann::json> records;
  std::istringstream lines(ReadText(run + "/frames.jsonl"));
  std::string line;
  while (std::getline(lines, line)) {
    nlohmann::json record = nlohmann::json::parse(line);
    record.erase("timings_ms");
    records.push_back(std::move(record));
  }
  return records;
}

TEST_F(SweepSlurm, TheSameSweepGivesTheSameRecordsAndScoresAsOnThisMachine) {
  const TempDir work;
  const std::string file =
      work.Write("grid.yaml", testing::GridSweep(Scene("lab"), Scene("occlusions")));
  Result r = Attend(work, {"sweep", file, "--out", "local", "--local", "2"});
  ASSERT_EQ(r.status, 0) << r.err;
  r = Attend(work, {"sweep", file, "--out", "slurm", "--slurm", "--throttle", "2"});
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string job = Trimmed(r.out);
  EXPECT_FALSE(job.empty());
  EXPECT_EQ(job.find_first_not_of("0123456789"), std::string::npos) << job;
  EXPECT_TRUE(Contains(ReadText(work.File("slurm/slurm/array-0.sbatch")), "--array=0-7%2"));
  const std::string status = WaitForSweep(work, work.File("slurm"), 240);
  ASSERT_TRUE(Contains(status, "8 cells: 8 done")) << status;
  // Each cell ran as a Slurm array task.
  const nlohmann::json cell_status = nlohmann::json::parse(
      ReadText(testing::DoneCells(work.File("slurm"))[0] + "/status.json"));
  EXPECT_EQ(cell_status["executor"], "slurm");
  EXPECT_TRUE(Contains(cell_status["slurm_task"].get<std::string>(), job + "_"));

  for (const char* sweep : {"local", "slurm"}) {
    r = Attend(work, {"sweep", sweep, "--collect"});
    ASSERT_EQ(r.status, 0) << r.err;
  }
  auto local = testing::ReadCsv(work.File("local/sweep.csv"));
  auto slurm = testing::ReadCsv(work.File("slurm/sweep.csv"));
  ASSERT_EQ(local.size(), 8u);
  ASSERT_EQ(slurm.size(), 8u);
  for (std::size_t i = 0; i < local.size(); ++i) {
    local[i].erase("seconds");
    slurm[i].erase("seconds");
    EXPECT_EQ(local[i], slurm[i]) << "row " << i;
    const std::string cell = "/cells/" + local[i].at("cell") + "/out";
    EXPECT_EQ(Records(work.File("local") + cell), Records(work.File("slurm") + cell)) << cell;
  }

  // Nothing left to submit.
  r = Attend(work, {"sweep", file, "--out", "slurm", "--slurm"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(Contains(r.out, "nothing to run: 8 of 8 cells done")) << r.out;
}

TEST_F(SweepSlurm, SbatchRefusingTheJobIsABadInputWithSlurmsMessage) {
  const TempDir work;
  const std::string file = work.Write(
      "sweep.yaml", "grid:\n  select.max_new: [1]\ninputs:\n  - sequence: " + Scene("lab") + "\n");
  const Result r =
      Attend(work, {"sweep", file, "--out", "s", "--slurm", "--partition", "no_such_partition"});
  EXPECT_EQ(r.status, 3) << r.err;
  EXPECT_TRUE(Contains(r.err, "sbatch refused")) << r.err;
  EXPECT_TRUE(Contains(r.err, "partition")) << r.err;  // Slurm's own words
}

TEST_F(SweepSlurm, ACellTheSchedulerStopsIsReportedKilledNotDone) {
  // A long cell: the lab scene at 8 times its size, 4 frames, one thread.
  const TempDir work;
  const std::string file = work.Write(
      "slow.yaml",
      "set:\n  threads: 1\n  sequence.width: 2560\n  sequence.height: 1920\n"
      "grid:\n  select.max_new: [1]\ninputs:\n  - sequence: " + Scene("lab") + "\n");
  Result r = Attend(work, {"sweep", file, "--out", "s", "--slurm"});
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string job = Trimmed(r.out);
  // Once its cell runs, the job is cancelled, as a time limit or an administrator would.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (!Contains(ReadText(work.File("s/cells") + "/" +
                            fs::directory_iterator(work.File("s/cells"))->path().filename().string() +
                            "/status.json"),
                   "\"running\"") &&
         std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  const Result cancelled = testing::Run("/usr/bin/scancel", work, {job});
  ASSERT_EQ(cancelled.status, 0) << cancelled.err;
  const std::string status = WaitForSweep(work, work.File("s"), 60);
  EXPECT_TRUE(Contains(status, "1 cells: 0 done, 0 running, 0 failed, 1 killed")) << status;
  EXPECT_TRUE(Contains(status, "stopped by Slurm") || Contains(status, "without a record"))
      << status;
  // It is not run again as missing; --retry-failed would.
  r = Attend(work, {"sweep", "s", "--slurm"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(Contains(r.out, "nothing to run: 0 of 1 cells done, 1 failed or killed")) << r.out;
  r = Attend(work, {"sweep", "s", "--collect"});
  ASSERT_EQ(r.status, 0) << r.err;
  const auto rows = testing::ReadCsv(work.File("s/sweep.csv"));
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0].at("state"), "killed");
}

TEST_F(SweepSlurm, ACellPastItsTimeLimitIsReportedAsATimeout) {
  // A cell of about two minutes (100 frames of the lab scene at 8 times its size) under a time
  // limit of one minute: Slurm ends it (SIGTERM, then SIGKILL after KillWait) between 60 and
  // 90 s, when its controller next checks the limits.
  const TempDir work;
  Result r = Attend(work, {"synth", (fs::path(testing::ProjectRoot()) / "sequences" / "lab.yaml")
                                        .string(),
                           "--out", "long", "--frames", "100", "--quiet"});
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string file = work.Write(
      "slow.yaml",
      "set:\n  threads: 1\n  sequence.width: 2560\n  sequence.height: 1920\n"
      "grid:\n  select.max_new: [1]\ninputs:\n  - sequence: " + work.File("long") + "\n"
      "slurm:\n  time: '1'\n");
  r = Attend(work, {"sweep", file, "--out", "s", "--slurm"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(Contains(ReadText(work.File("s/slurm/array-0.sbatch")), "#SBATCH --time=1\n"));
  // The cell records itself killed at Slurm's SIGTERM; Slurm says TIMEOUT once the task ends.
  const std::string status = WaitForSweep(work, work.File("s"), 180, "(Slurm: TIMEOUT)");
  EXPECT_TRUE(Contains(status, "1 cells: 0 done, 0 running, 0 failed, 1 killed")) << status;
  EXPECT_TRUE(Contains(status, "(Slurm: TIMEOUT)")) << status;
}

}  // namespace
}  // namespace attend
