// The sweep file's expansion into cells (app/sweep_plan.h) and Slurm's array value
// (app/sweep_slurm.h), on inputs whose answer is known by construction.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "app/sweep_plan.h"
#include "app/sweep_slurm.h"
#include "tests/support/error_message.h"
#include "tests/support/sequence_maker.h"
#include "tests/support/temp_dir.h"

namespace attend {
namespace {

using testing::TempDir;

TEST(SlurmArraySpec, RunsOfIndexesBecomeRanges) {
  EXPECT_EQ(SlurmArraySpec({0, 1, 2, 3}, 0), "0-3");
  EXPECT_EQ(SlurmArraySpec({5, 0, 1, 3, 9, 8, 7}, 2), "0-1,3,5,7-9%2");
  EXPECT_EQ(SlurmArraySpec({4, 4, 4}, 0), "4");
}

// A sequence folder with a gt/objects.csv, enough for the plan's checks.
std::string SequenceWithTruth(const TempDir& dir, const std::string& name) {
  const std::string folder = testing::MakeFolderSequence(dir.File(name), 2, 32, 24);
  std::filesystem::create_directories(std::filesystem::path(folder) / "gt");
  dir.Write(name + "/gt/objects.csv", "frame,id,x,y,w,h\n");
  return folder;
}

TEST(SweepPlan, GridTimesZipTimesInputsInOrderWithStableNames) {
  const TempDir dir;
  SequenceWithTruth(dir, "a");
  SequenceWithTruth(dir, "b");
  const std::string sweep = "grid:\n  select.max_new: [1, 2]\n  select.min_area: [50, 60, 70]\n"
                            "zip:\n  inhibition.margin: [0, 4]\n  select.min_saliency: [0.1, 0.3]\n"
                            "inputs:\n  - sequence: a\n  - sequence: b\n";
  const SweepPlan plan = ReadSweepFile(dir.Write("s.yaml", sweep));
  ASSERT_EQ(plan.cells.size(), 2u * 3u * 2u * 2u);
  EXPECT_EQ(plan.keys, (std::vector<std::string>{"select.max_new", "select.min_area",
                                                 "inhibition.margin", "select.min_saliency"}));
  // The first configuration over both inputs, then the zip's next step, then the grid's last key.
  EXPECT_EQ(plan.cells[0].settings[0].second, "1");
  EXPECT_EQ(plan.cells[0].input, 0);
  EXPECT_EQ(plan.cells[1].input, 1);
  EXPECT_EQ(plan.cells[2].settings[2].second, "4");
  EXPECT_EQ(plan.cells[2].settings[3].second, "0.3");
  EXPECT_EQ(plan.cells[4].settings[1].second, "60");
  std::set<std::string> names;
  for (const SweepCell& cell : plan.cells) names.insert(cell.name);
  EXPECT_EQ(names.size(), plan.cells.size());

  // Another value for a key: the cells that were there keep their names.
  std::string grown = sweep;
  grown.replace(grown.find("[1, 2]"), 6, "[1, 2, 3]");
  const SweepPlan bigger = ReadSweepFile(dir.Write("s.yaml", grown));
  std::set<std::string> bigger_names;
  for (const SweepCell& cell : bigger.cells) bigger_names.insert(cell.name);
  for (const std::string& name : names) EXPECT_TRUE(bigger_names.count(name)) << name;
  EXPECT_EQ(bigger.cells.size(), 36u);
}

TEST(SweepPlan, ErrorsNameTheLineAndTheKey) {
  const TempDir dir;
  SequenceWithTruth(dir, "a");
  const std::string message = testing::ConfigErrorOf([&] {
    ReadSweepFile(dir.Write("s.yaml", "set:\n  threads: 1\ngrid:\n  select.max_new: [1]\n"
                                      "  select.max_new_x: [2]\ninputs:\n  - sequence: a\n"));
  });
  EXPECT_NE(message.find("s.yaml:5: grid.select.max_new_x: "), std::string::npos) << message;
  const std::string twice = testing::ConfigErrorOf([&] {
    ReadSweepFile(dir.Write("s.yaml", "set:\n  select.max_new: 1\ngrid:\n  select.max_new: [1]\n"
                                      "inputs:\n  - sequence: a\n"));
  });
  EXPECT_NE(twice.find("also given at"), std::string::npos) << twice;
  const std::string track = testing::ConfigErrorOf([&] {
    ReadSweepFile(dir.Write("s.yaml", "command: track\ngrid:\n  select.max_new: [1]\n"
                                      "inputs:\n  - sequence: a\n    gt: a/gt/objects.csv\n"));
  });
  EXPECT_NE(track.find("command track takes only tracker.* keys"), std::string::npos) << track;
}

}  // namespace
}  // namespace attend
