// attend sweep against bad input of issue 46: a grid too large to plan, an input's frames that
// cannot be, a sweep file that is a fifo or a device, and a sweep folder's records edited by
// hand (status.json, scores.json, cell.json, sweep.json). Each is refused at once naming the
// file and the key, or the cell is recorded as not run and the others are kept.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
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

class SweepRecords : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new TempDir();
    testing::RenderSweepScenes(*dir_);
    // A finished sweep of two cells, copied by the tests that damage it.
    const std::string file = dir_->Write(
        "sweep.yaml", "set: {threads: 1}\ngrid:\n  select.max_new: [1, 2]\ninputs:\n"
                      "  - sequence: " + dir_->File("lab") + "\n");
    const Result r = Attend(*dir_, {"sweep", file, "--out", "done", "--local", "2"});
    ASSERT_EQ(r.status, 0) << r.err;
  }
  static void TearDownTestSuite() {
    delete dir_;
    dir_ = nullptr;
  }
  static std::string Scene(const std::string& name) { return dir_->File(name); }
  // A copy of the finished sweep in `work`/s, its paths made its own.
  static std::string CopyOfDoneSweep(const TempDir& work) {
    const std::string sweep = work.File("s");
    fs::copy(dir_->File("done"), sweep, fs::copy_options::recursive);
    for (const auto& entry : fs::recursive_directory_iterator(sweep)) {
      const std::string name = entry.path().filename().string();
      if (name != "sweep.json" && name != "cell.json") continue;
      std::string text = ReadText(entry.path().string());
      for (std::size_t at; (at = text.find(dir_->File("done"))) != std::string::npos;) {
        text.replace(at, dir_->File("done").size(), sweep);
      }
      std::ofstream(entry.path()) << text;
    }
    return sweep;
  }
  static std::vector<std::string> Cells(const std::string& sweep) {
    const nlohmann::json json = nlohmann::json::parse(ReadText(sweep + "/sweep.json"));
    std::vector<std::string> cells;
    for (const auto& cell : json["cells"]) cells.push_back(sweep + "/cells/" + cell["name"].get<std::string>());
    return cells;
  }

  static TempDir* dir_;
};

TempDir* SweepRecords::dir_ = nullptr;

// CPU seconds of the children reaped so far: what a command costs, whatever else loads the
// machine.
double ChildrenCpuSeconds() {
  rusage usage{};
  getrusage(RUSAGE_CHILDREN, &usage);
  return static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
         static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec) / 1e6;
}

TEST_F(SweepRecords, AGridOfTooManyCellsIsRefusedAtOnceNamingItsLists) {
  const TempDir work;
  std::string thousand;
  for (int i = 1; i <= 1000; ++i) thousand += (i > 1 ? ", " : "") + std::to_string(i);
  const std::string file = work.Write(
      "sweep.yaml", "grid:\n  select.max_new: [" + thousand + "]\n  select.min_area: [" +
                        thousand + "]\ninputs:\n  - sequence: " + Scene("lab") + "\n");
  const double start = ChildrenCpuSeconds();
  Result r = Attend(work, {"sweep", file, "--out", "s"});
  const double seconds = ChildrenCpuSeconds() - start;
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_TRUE(Contains(r.err, "sweep.yaml:2: the sweep has 1000000 cells (grid.select.max_new: "
                              "1000 x grid.select.min_area: 1000 x inputs: 1), more than the "
                              "10000 a sweep may have (docs/LIMITS.md)"))
      << r.err;
  EXPECT_LT(seconds, 2.0);  // refused before a combination is made
  EXPECT_FALSE(fs::exists(work.File("s")));

  // A list of 20,000 values for one key (10^5 values are past the YAML reader's own cap).
  std::string many;
  for (int i = 0; i < 20000; ++i) many += (i > 0 ? "," : "") + std::to_string(i);
  work.Write("one.yaml", "grid:\n  select.min_area: [" + many + "]\ninputs:\n  - sequence: " +
                             Scene("lab") + "\n");
  r = Attend(work, {"sweep", work.File("one.yaml"), "--dry-run"});
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_TRUE(Contains(r.err, "the sweep has 20000 cells (grid.select.min_area: 20000 x "
                              "inputs: 1)"))
      << r.err;
}

TEST_F(SweepRecords, TheLargestGridPlansInSeconds) {
  const TempDir work;
  std::string hundred;
  for (int i = 1; i <= 100; ++i) hundred += (i > 1 ? ", " : "") + std::to_string(i);
  const std::string file = work.Write(
      "sweep.yaml", "grid:\n  select.max_new: [" + hundred + "]\n  select.min_area: [" +
                        hundred + "]\ninputs:\n  - sequence: " + Scene("lab") + "\n");
  const double start = ChildrenCpuSeconds();
  const Result r = Attend(work, {"sweep", file, "--dry-run"});
  const double seconds = ChildrenCpuSeconds() - start;
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(Contains(r.out, "10000 cells of attend run")) << r.out.substr(0, 200);
  // Each combination read the base configuration file anew: 15 s of parsing here; now 2.5 s.
  // AddressSanitizer's build (scripts/sanitize.sh) runs the same work about ten times slower.
#if defined(__SANITIZE_ADDRESS__)
  constexpr double kBound = 80.0;
#else
  constexpr double kBound = 8.0;
#endif
  EXPECT_LT(seconds, kBound);
}

TEST_F(SweepRecords, AnInputsFramesAndTheSweepFileItselfAreCheckedBeforeAnyCell) {
  const TempDir work;
  work.Write("frames.yaml", "grid:\n  select.max_new: [1]\ninputs:\n  - sequence: " +
                                Scene("lab") + "\n    frames: \"9:2\"\n");
  Result r = Attend(work, {"sweep", work.File("frames.yaml"), "--out", "s"});
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_TRUE(Contains(r.err, "frames.yaml:5: inputs[0].frames: --frames 9:2: the range ends"))
      << r.err;
  work.Write("frames.yaml", "grid:\n  select.max_new: [1]\ninputs:\n  - sequence: " +
                                Scene("lab") + "\n    frames: \"a:b\"\n");
  r = Attend(work, {"sweep", work.File("frames.yaml"), "--out", "s"});
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_TRUE(Contains(r.err, "frames.yaml:5: inputs[0].frames: ")) << r.err;
  EXPECT_FALSE(fs::exists(work.File("s")));

  ASSERT_EQ(mkfifo(work.File("fifo").c_str(), 0644), 0);
  r = Attend(work, {"sweep", "fifo", "--out", "s"});
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_TRUE(Contains(r.err, "fifo: the sweep file is a fifo (named pipe), not a file")) << r.err;
  r = Attend(work, {"sweep", "/dev/zero", "--out", "s"});
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_TRUE(Contains(r.err, "/dev/zero: the sweep file is a character device")) << r.err;
  r = Attend(work, {"sweep", "missing.yaml", "--out", "s"});
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_TRUE(Contains(r.err, "missing.yaml: the sweep file does not exist")) << r.err;
  // Larger than a configuration may be: refused by its size, not read.
  {
    std::ofstream big(work.File("big.yaml"));
    big << "# " << std::string((16u << 20) + 10, 'x') << "\n";
  }
  r = Attend(work, {"sweep", "big.yaml", "--out", "s"});
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_TRUE(Contains(r.err, "more than 16 MB")) << r.err;
  EXPECT_FALSE(fs::exists(work.File("s")));
}

TEST_F(SweepRecords, AStatusJsonEditedByHandNamesItsKeyAndTheCellRunsAgain) {
  const TempDir work;
  const std::string sweep = CopyOfDoneSweep(work);
  const std::vector<std::string> cells = Cells(sweep);
  std::string status = ReadText(cells[0] + "/status.json");
  status.replace(status.find("\"exit_status\": 0"), 16, "\"exit_status\": \"zero\"");
  std::ofstream(cells[0] + "/status.json") << status;

  Result r = Attend(work, {"sweep", sweep, "--status"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(Contains(r.out, "1 done, 0 running, 0 failed, 0 killed, 1 waiting")) << r.out;
  EXPECT_TRUE(Contains(r.out, cells[0] + "/status.json: exit_status: expected an integer, found "
                                         "the string \"zero\"; the cell runs again"))
      << r.out;
  r = Attend(work, {"sweep", sweep, "--collect"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(Contains(r.err, "status.json: exit_status: ")) << r.err;
  const auto rows = testing::ReadCsv(sweep + "/sweep.csv");
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].at("state"), "waiting");
  EXPECT_EQ(rows[1].at("state"), "done");
  EXPECT_NE(rows[1].at("coverage"), "");
  r = Attend(work, {"sweep", sweep});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(Contains(r.out, "1 of 1 cells done")) << r.out;
  EXPECT_EQ(testing::DoneCells(sweep).size(), 2u);
}

TEST_F(SweepRecords, ScoresThatAreNotAMapOfNumbersAreRefusedNamingTheFile) {
  for (const auto& [scores, expected] : std::vector<std::pair<std::string, std::string>>{
           {"[0.5, 0.25, 1]", "scores.json: expected a JSON object, found an array"},
           {"{\"coverage\": \"high\"}",
            "scores.json: coverage: expected a number or null (a score), found the string "
            "\"high\""},
           {"{\"coverage\": 0.5", "scores.json: not valid JSON ("},
           {"", "scores.json: not valid JSON ("}}) {
    const TempDir work;
    const std::string sweep = CopyOfDoneSweep(work);
    const std::vector<std::string> cells = Cells(sweep);
    std::ofstream(cells[1] + "/scores.json") << scores;
    Result r = Attend(work, {"sweep", sweep, "--collect"});
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(Contains(r.err, cells[1] + "/" + expected)) << scores << ": " << r.err;
    const std::string csv = ReadText(sweep + "/sweep.csv");
    EXPECT_FALSE(Contains(csv, ",0,1,2")) << csv;
    const auto rows = testing::ReadCsv(sweep + "/sweep.csv");
    ASSERT_EQ(rows.size(), 2u);
    EXPECT_EQ(rows[0].at("state"), "done");
    EXPECT_EQ(rows[1].at("state"), "waiting");
    r = Attend(work, {"sweep", sweep});
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_TRUE(Contains(r.out, "1 of 1 cells done")) << r.out;
  }
}

TEST_F(SweepRecords, ADamagedCellJsonOrSweepJsonIsRefusedNamingTheFileAndKey) {
  const TempDir work;
  const std::string sweep = CopyOfDoneSweep(work);
  const std::vector<std::string> cells = Cells(sweep);
  std::ofstream(cells[0] + "/cell.json") << "{\"commands\": 3}";
  Result r = Attend(work, {"sweep", sweep});
  EXPECT_EQ(r.status, 3) << r.err;
  EXPECT_TRUE(Contains(r.err, cells[0] + "/cell.json: commands: expected a list of lists of "
                                         "strings, found the number 3; remove the folder " +
                                         cells[0] + " to run the cell again"))
      << r.err;
  r = Attend(work, {"sweep", sweep, "--cell", "0"});
  EXPECT_EQ(r.status, 3) << r.err;
  EXPECT_TRUE(Contains(r.err, "cell.json: commands: ")) << r.err;
  // --collect keeps the cell's scores and says what it left out.
  r = Attend(work, {"sweep", sweep, "--collect"});
  EXPECT_EQ(r.status, 0) << r.err;

  std::string json = ReadText(sweep + "/sweep.json");
  json.replace(json.find("\"cpus_per_task\": 1"), 18, "\"cpus_per_task\": \"one\"");
  std::ofstream(sweep + "/sweep.json") << json;
  for (const std::vector<std::string>& words :
       {std::vector<std::string>{"sweep", sweep, "--status"},
        std::vector<std::string>{"sweep", sweep, "--collect"},
        std::vector<std::string>{"sweep", sweep}}) {
    r = Attend(work, words);
    EXPECT_EQ(r.status, 3) << r.err;
    EXPECT_TRUE(Contains(r.err, sweep + "/sweep.json: slurm.cpus_per_task: expected an integer, "
                                        "found the string \"one\""))
        << r.err;
  }
  // A cell name that would be a path elsewhere.
  json = ReadText(dir_->File("done/sweep.json"));
  const nlohmann::json parsed = nlohmann::json::parse(json);
  const std::string name = parsed["cells"][0]["name"];
  json.replace(json.find("\"" + name + "\""), name.size() + 2, "\"../../elsewhere\"");
  std::ofstream(sweep + "/sweep.json") << json;
  r = Attend(work, {"sweep", sweep, "--status"});
  EXPECT_EQ(r.status, 3) << r.err;
  EXPECT_TRUE(Contains(r.err, "sweep.json: cells[0].name: '../../elsewhere' is not a cell "
                              "folder's name"))
      << r.err;
}

}  // namespace
}  // namespace attend
