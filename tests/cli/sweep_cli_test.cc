// attend sweep on this machine, end to end (docs/SWEEPS.md): a 2 x 2 grid over two rendered
// scenes, each cell's configuration and scores checked against attend run and attend eval; an
// interrupted sweep run again; a failing cell; a changed sweep file; bad sweep files.
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

#include "eval/run_comparison.h"
#include "tests/cli/attend_cli.h"
#include "tests/cli/sweep_support.h"
#include "tests/support/attend_process.h"
#include "tests/support/sequence_maker.h"
#include "tests/support/temp_dir.h"

namespace fs = std::filesystem;

namespace attend {
namespace {

using testing::Attend;
using testing::Contains;
using testing::ReadText;
using testing::Result;
using testing::TempDir;

class SweepCli : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new TempDir();
    testing::RenderSweepScenes(*dir_);
    // A copy of the lab scene with one frame that is not an image: its cells fail.
    fs::copy(dir_->path() / "lab", dir_->path() / "broken", fs::copy_options::recursive);
    testing::CorruptFrame(dir_->File("broken"), "left", 2);
  }
  static void TearDownTestSuite() {
    delete dir_;
    dir_ = nullptr;
  }
  static std::string Scene(const std::string& name) { return dir_->File(name); }

  static TempDir* dir_;
};

TempDir* SweepCli::dir_ = nullptr;

std::vector<std::string> CellFolders(const std::string& sweep) {
  std::vector<std::string> cells;
  for (const auto& entry : fs::directory_iterator(fs::path(sweep) / "cells")) {
    cells.push_back(entry.path().string());
  }
  std::sort(cells.begin(), cells.end());
  return cells;
}

TEST_F(SweepCli, GridCellsCarryTheirSettingsAndCollectGivesEvalsScores) {
  const TempDir work;
  const std::string file =
      work.Write("grid.yaml", testing::GridSweep(Scene("lab"), Scene("occlusions")));
  Result r = Attend(work, {"sweep", file, "--out", "s", "--local", "2"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(Contains(r.out, "8 of 8 cells done, 0 failed")) << r.out;

  // A run of the base configuration: every key but the swept ones is as there.
  r = Attend(work, {"run", "--sequence", Scene("lab"), "--out", "base", "--quiet"});
  ASSERT_EQ(r.status, 0) << r.err;
  const FlatConfig base = FlattenConfigFile(work.File("base/config.yaml"));

  const std::vector<std::string> cells = CellFolders(work.File("s"));
  ASSERT_EQ(cells.size(), 8u);
  std::set<std::pair<std::string, std::string>> combinations;
  for (const std::string& cell : cells) {
    const nlohmann::json description =
        nlohmann::json::parse(ReadText((fs::path(cell) / "cell.json").string()));
    const std::string weight = description["settings"]["features.colour_contrast.weight"];
    const std::string max_new = description["settings"]["select.max_new"];
    combinations.insert({description["input"]["name"].get<std::string>() + weight, max_new});
    EXPECT_EQ(description["attend_version"], "0.1.0");
    ASSERT_EQ(description["reproduce"].size(), 2u);
    EXPECT_TRUE(Contains(description["reproduce"][0], "attend run --config "));

    // The run's effective configuration is the base with this cell's values.
    const FlatConfig config = FlattenConfigFile((fs::path(cell) / "out" / "config.yaml").string());
    EXPECT_EQ(ReadText((fs::path(cell) / "config.yaml").string()).empty(), false);
    for (const auto& [key, value] : config) {
      if (key.rfind("sequence.", 0) == 0) continue;  // the input
      if (key == "features.colour_contrast.weight") {
        EXPECT_DOUBLE_EQ(std::stod(value), std::stod(weight)) << cell;
      } else if (key == "select.max_new") {
        EXPECT_EQ(value, max_new) << cell;
      } else if (key == "threads") {
        EXPECT_EQ(value, "1") << cell;  // the sweep's set
      } else {
        ASSERT_TRUE(base.count(key)) << key;
        EXPECT_EQ(value, base.at(key)) << cell << ": " << key;
      }
    }
  }
  EXPECT_EQ(combinations.size(), 8u);

  r = Attend(work, {"sweep", "s", "--collect"});
  ASSERT_EQ(r.status, 0) << r.err;
  const std::vector<std::map<std::string, std::string>> rows =
      testing::ReadCsv(work.File("s/sweep.csv"));
  ASSERT_EQ(rows.size(), 8u);
  for (const auto& row : rows) {
    EXPECT_EQ(row.at("state"), "done");
    const std::string out = work.File("s/cells/" + row.at("cell") + "/out");
    const Result eval = Attend(work, {"eval", out});
    ASSERT_EQ(eval.status, 0) << eval.err;
    const nlohmann::json scores = nlohmann::json::parse(eval.out);
    for (const char* key : {"coverage", "mean_latency", "revisits", "identity_switches",
                            "mean_iou", "attended"}) {
      EXPECT_NEAR(std::stod(row.at(key)), scores[key].get<double>(), 1e-8) << key;
    }
    EXPECT_NEAR(std::stod(row.at("mot.iou_0.5.IDF1")),
                scores["mot"]["iou_0.5"]["IDF1"].get<double>(), 1e-8);
    EXPECT_NEAR(std::stod(row.at("mot.iou_0.5.MOTA")),
                scores["mot"]["iou_0.5"]["MOTA"].get<double>(), 1e-8);
  }
  const std::string html = ReadText(work.File("s/report.html"));
  EXPECT_TRUE(Contains(html, "class=\"sortable\""));
  EXPECT_TRUE(Contains(html, "Best configuration per score"));
  EXPECT_TRUE(Contains(html, "plot-1"));  // a plot for each of the two keys

  // The same sweep again: nothing to run.
  r = Attend(work, {"sweep", file, "--out", "s"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(Contains(r.out, "nothing to run: 8 of 8 cells done")) << r.out;
  r = Attend(work, {"sweep", "s", "--status"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(Contains(r.out, "8 cells: 8 done, 0 running, 0 failed, 0 killed, 0 waiting"))
      << r.out;
}

TEST_F(SweepCli, AnInterruptedSweepRunsOnlyTheMissingCellsAgain) {
  const TempDir work;
  const std::string file =
      work.Write("grid.yaml", testing::GridSweep(Scene("lab"), Scene("occlusions")));
  const pid_t pid = testing::StartAttend(work, {"sweep", file, "--out", "s", "--local", "1"});
  // Stopped once two cells are done.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (testing::DoneCells(work.File("s")).size() < 2 &&
         std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  kill(pid, SIGINT);
  const Result stopped = testing::Wait(work, pid);
  const std::vector<std::string> done = testing::DoneCells(work.File("s"));
  ASSERT_GE(done.size(), 2u);
  if (done.size() == 8u) GTEST_SKIP() << "the sweep ended before the interrupt reached it";
  EXPECT_EQ(stopped.status, 128 + SIGINT) << stopped.out << stopped.err;
  EXPECT_TRUE(Contains(stopped.out, "stopped by")) << stopped.out;
  std::map<std::string, std::string> started;
  for (const std::string& cell : done) {
    started[cell] = nlohmann::json::parse(ReadText(cell + "/status.json"))["started"];
  }

  const Result again = Attend(work, {"sweep", file, "--out", "s", "--local", "2"});
  ASSERT_EQ(again.status, 0) << again.err;
  const std::string expected = std::to_string(8 - done.size()) + " of " +
                               std::to_string(8 - done.size()) + " cells done";
  EXPECT_TRUE(Contains(again.out, expected)) << again.out;
  EXPECT_EQ(testing::DoneCells(work.File("s")).size(), 8u);
  for (const auto& [cell, time] : started) {
    EXPECT_EQ(nlohmann::json::parse(ReadText(cell + "/status.json"))["started"], time)
        << cell << " ran again";
  }
}

TEST_F(SweepCli, AFailingCellIsRecordedAndTheOthersGoOn) {
  const TempDir work;
  const std::string file = work.Write(
      "sweep.yaml", "set: {threads: 1}\ngrid:\n  select.max_new: [1, 2]\ninputs:\n"
                    "  - sequence: " + Scene("lab") + "\n  - sequence: " + Scene("broken") + "\n");
  Result r = Attend(work, {"sweep", file, "--out", "s", "--local", "2"});
  EXPECT_EQ(r.status, 3) << r.out << r.err;
  EXPECT_TRUE(Contains(r.out, "2 of 4 cells done, 2 failed")) << r.out;
  r = Attend(work, {"sweep", "s", "--status"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(Contains(r.out, "2 done, 0 running, 2 failed")) << r.out;
  EXPECT_TRUE(Contains(r.out, "exit status 3: run: ")) << r.out;
  EXPECT_TRUE(Contains(r.out, "000002")) << r.out;  // the frame that is not an image

  r = Attend(work, {"sweep", "s", "--collect"});
  ASSERT_EQ(r.status, 0) << r.err;
  const auto rows = testing::ReadCsv(work.File("s/sweep.csv"));
  ASSERT_EQ(rows.size(), 4u);
  int failed = 0;
  for (const auto& row : rows) {
    if (row.at("input") == "broken") {
      EXPECT_EQ(row.at("state"), "failed");
      EXPECT_EQ(row.at("exit_status"), "3");
      EXPECT_EQ(row.at("coverage"), "");
      ++failed;
    } else {
      EXPECT_EQ(row.at("state"), "done");
      EXPECT_NE(row.at("coverage"), "");
    }
  }
  EXPECT_EQ(failed, 2);

  // Run again: nothing; --retry-failed: only the two failed cells.
  r = Attend(work, {"sweep", "s"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(Contains(r.out, "nothing to run: 2 of 4 cells done, 2 failed")) << r.out;
  r = Attend(work, {"sweep", "s", "--retry-failed", "--local", "2"});
  EXPECT_EQ(r.status, 3) << r.err;
  EXPECT_TRUE(Contains(r.out, "0 of 2 cells done, 2 failed")) << r.out;
}

TEST_F(SweepCli, AChangedSweepFileNeedsExtendAndKeepsTheOldCells) {
  const TempDir work;
  const std::string lab = Scene("lab");
  work.Write("a.yaml", "set: {threads: 1}\ngrid:\n  select.max_new: [1]\ninputs:\n  - sequence: " +
                           lab + "\n");
  Result r = Attend(work, {"sweep", work.File("a.yaml"), "--out", "s"});
  ASSERT_EQ(r.status, 0) << r.err;
  work.Write("a.yaml", "set: {threads: 1}\ngrid:\n  select.max_new: [1, 2]\ninputs:\n"
                       "  - sequence: " + lab + "\n");
  r = Attend(work, {"sweep", work.File("a.yaml"), "--out", "s"});
  EXPECT_EQ(r.status, 2);
  EXPECT_TRUE(Contains(r.err, "1 cells are new")) << r.err;
  EXPECT_TRUE(Contains(r.err, "--extend")) << r.err;
  r = Attend(work, {"sweep", work.File("a.yaml"), "--out", "s", "--extend"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(Contains(r.out, "1 of 1 cells done")) << r.out;
  const nlohmann::json sweep = nlohmann::json::parse(ReadText(work.File("s/sweep.json")));
  ASSERT_EQ(sweep["cells"].size(), 2u);
  EXPECT_EQ(sweep["cells"][0]["settings"]["select.max_new"], "1");
  EXPECT_EQ(sweep["cells"][1]["settings"]["select.max_new"], "2");

  // A changed base (the fixed sets) changes what every cell runs: another sweep, always.
  work.Write("a.yaml", "set: {threads: 2}\ngrid:\n  select.max_new: [1, 2]\ninputs:\n"
                       "  - sequence: " + lab + "\n");
  r = Attend(work, {"sweep", work.File("a.yaml"), "--out", "s", "--extend"});
  EXPECT_EQ(r.status, 2);
  EXPECT_TRUE(Contains(r.err, "would now run other commands")) << r.err;
}

TEST_F(SweepCli, ZippedListsChangeTogetherAndListValuedKeysSweep) {
  const TempDir work;
  const std::string file = work.Write(
      "zip.yaml",
      "set: {threads: 1}\n"
      "zip:\n"
      "  select.max_new: [1, 3]\n"
      "  select.min_area: [100, 200]\n"
      "grid:\n"
      "  features:\n"
      "    - [{name: colour_contrast}]\n"
      "    - [{name: colour_contrast}, {name: intensity_contrast, weight: 0.5}]\n"
      "inputs:\n  - sequence: " + Scene("lab") + "\n");
  Result r = Attend(work, {"sweep", file, "--dry-run"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(Contains(r.out, "4 cells of attend run")) << r.out;
  EXPECT_TRUE(Contains(r.out, "select.max_new=1 select.min_area=100")) << r.out;
  EXPECT_TRUE(Contains(r.out, "select.max_new=3 select.min_area=200")) << r.out;
  EXPECT_FALSE(Contains(r.out, "select.max_new=1 select.min_area=200")) << r.out;
  EXPECT_FALSE(fs::exists(work.File("s")));
  r = Attend(work, {"sweep", file, "--out", "s", "--local", "2"});
  ASSERT_EQ(r.status, 0) << r.err;
  for (const std::string& cell : CellFolders(work.File("s"))) {
    const FlatConfig config = FlattenConfigFile(cell + "/out/config.yaml");
    const bool two = config.count("features.intensity_contrast.weight") != 0;
    if (two) {
      EXPECT_DOUBLE_EQ(std::stod(config.at("features.intensity_contrast.weight")), 0.5);
    }
    EXPECT_EQ(config.at("select.max_new") == "1", config.at("select.min_area") == "100") << cell;
  }
}

struct BadSweep {
  std::string name;
  std::string yaml;      // LAB stands for the lab scene's folder
  std::string expected;  // in the message
};

TEST_F(SweepCli, BadSweepFilesStopBeforeAnyCellRuns) {
  const std::vector<BadSweep> cases = {
      {"unknown key", "grid:\n  select.max_nwe: [1, 2]\ninputs:\n  - sequence: LAB\n",
       "sweep.yaml:2: grid.select.max_nwe: "},
      {"out of range", "grid:\n  select.max_new:\n    - 1\n    - -4\ninputs:\n  - sequence: LAB\n",
       "sweep.yaml:4: grid.select.max_new: "},
      {"missing input", "grid:\n  select.max_new: [1]\ninputs:\n  - sequence: LAB\n"
                        "  - sequence: /no/such/scene\n",
       "sweep.yaml:5: inputs[1].sequence: /no/such/scene: no such folder"},
      {"empty grid", "grid: {}\ninputs:\n  - sequence: LAB\n", "sweep.yaml:1: grid: empty"},
      {"empty list", "grid:\n  select.max_new: []\ninputs:\n  - sequence: LAB\n",
       "grid.select.max_new: an empty list"},
      {"unequal zip", "zip:\n  select.max_new: [1, 2]\n  select.min_area: [100]\ninputs:\n"
                      "  - sequence: LAB\n",
       "the same length"},
      {"unknown section", "gird:\n  select.max_new: [1]\ninputs:\n  - sequence: LAB\n",
       "sweep.yaml:1: gird: unknown key (did you mean 'grid'?)"},
      {"no inputs", "grid:\n  select.max_new: [1]\n", "inputs: missing"},
      {"no ground truth", "grid:\n  select.max_new: [1]\ninputs:\n  - images: LAB/left\n",
       "give gt:"},
  };
  for (const BadSweep& bad : cases) {
    const TempDir work;
    std::string yaml = bad.yaml;
    for (std::size_t at; (at = yaml.find("LAB")) != std::string::npos;) {
      yaml.replace(at, 3, Scene("lab"));
    }
    const std::string file = work.Write("sweep.yaml", yaml);
    const Result r = Attend(work, {"sweep", file, "--out", "s"});
    EXPECT_EQ(r.status, 2) << bad.name << ": " << r.err;
    EXPECT_TRUE(Contains(r.err, bad.expected)) << bad.name << ": " << r.err;
    EXPECT_FALSE(fs::exists(work.File("s"))) << bad.name << ": the folder was made";
  }
}

TEST_F(SweepCli, SbatchMissingIsABadInputWithItsReason) {
  const TempDir work;
  const std::string file = work.Write(
      "sweep.yaml", "grid:\n  select.max_new: [1]\ninputs:\n  - sequence: " + Scene("lab") + "\n");
  const std::string path = std::getenv("PATH") != nullptr ? std::getenv("PATH") : "";
  setenv("PATH", work.File("nothing").c_str(), 1);
  const Result r = Attend(work, {"sweep", file, "--out", "s", "--slurm"});
  setenv("PATH", path.c_str(), 1);
  EXPECT_EQ(r.status, 3) << r.err;
  EXPECT_TRUE(Contains(r.err, "sbatch: ")) << r.err;
  EXPECT_TRUE(Contains(r.err, "slurm-client")) << r.err;
  // Nothing ran: the cell still waits.
  const Result status = Attend(work, {"sweep", "s", "--status"});
  EXPECT_TRUE(Contains(status.out, "1 cells: 0 done, 0 running, 0 failed, 0 killed, 1 waiting"))
      << status.out << status.err;
}

TEST_F(SweepCli, DryRunWithSlurmPrintsTheBatchScript) {
  const TempDir work;
  const std::string file = work.Write(
      "sweep.yaml", "grid:\n  select.max_new: [1, 2, 3]\ninputs:\n  - sequence: " +
                        Scene("lab") + "\nslurm: {partition: lab, time: '00:10:00', throttle: 2}\n");
  const Result r = Attend(work, {"sweep", file, "--out", "s", "--slurm", "--dry-run", "--mem",
                                 "2G"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(Contains(r.out, "#SBATCH --array=0-2%2")) << r.out;
  EXPECT_TRUE(Contains(r.out, "#SBATCH --partition=lab")) << r.out;
  EXPECT_TRUE(Contains(r.out, "#SBATCH --time=00:10:00")) << r.out;
  EXPECT_TRUE(Contains(r.out, "#SBATCH --mem=2G")) << r.out;
  EXPECT_TRUE(Contains(r.out, "--cell \"$SLURM_ARRAY_TASK_ID\"")) << r.out;
  EXPECT_FALSE(fs::exists(work.File("s")));
}

}  // namespace
}  // namespace attend
