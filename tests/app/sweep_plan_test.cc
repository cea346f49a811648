// The planning of a sweep file in its steps (app/sweep_plan.h: read, check, expand), its
// inputs' sources (app/sweep_inputs.h), the scenes rendered when the folder is prepared
// (app/sweep_folder.h) and Slurm's array value (app/sweep_slurm.h), on inputs whose answer is
// known by construction.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "app/sweep_folder.h"
#include "app/sweep_inputs.h"
#include "app/sweep_plan.h"
#include "app/sweep_slurm.h"
#include "tests/support/error_message.h"
#include "tests/support/kitti_maker.h"
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
  const SweepPlan plan = PlanSweep(dir.Write("s.yaml", sweep));
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
  const SweepPlan bigger = PlanSweep(dir.Write("s.yaml", grown));
  std::set<std::string> bigger_names;
  for (const SweepCell& cell : bigger.cells) bigger_names.insert(cell.name);
  for (const std::string& name : names) EXPECT_TRUE(bigger_names.count(name)) << name;
  EXPECT_EQ(bigger.cells.size(), 36u);
}

TEST(SweepPlan, ErrorsNameTheLineAndTheKey) {
  const TempDir dir;
  SequenceWithTruth(dir, "a");
  const std::string message = testing::ConfigErrorOf([&] {
    PlanSweep(dir.Write("s.yaml", "set:\n  threads: 1\ngrid:\n  select.max_new: [1]\n"
                                      "  select.max_new_x: [2]\ninputs:\n  - sequence: a\n"));
  });
  EXPECT_NE(message.find("s.yaml:5: grid.select.max_new_x: "), std::string::npos) << message;
  const std::string twice = testing::ConfigErrorOf([&] {
    PlanSweep(dir.Write("s.yaml", "set:\n  select.max_new: 1\ngrid:\n  select.max_new: [1]\n"
                                      "inputs:\n  - sequence: a\n"));
  });
  EXPECT_NE(twice.find("also given at"), std::string::npos) << twice;
  const std::string track = testing::ConfigErrorOf([&] {
    PlanSweep(dir.Write("s.yaml", "command: track\ngrid:\n  select.max_new: [1]\n"
                                      "inputs:\n  - sequence: a\n    gt: a/gt/objects.csv\n"));
  });
  EXPECT_NE(track.find("command track takes only tracker.* keys"), std::string::npos) << track;
}

TEST(SweepPlan, TheStepsReadThenCheckThenExpand) {
  const TempDir dir;
  SequenceWithTruth(dir, "a");
  const std::string file =
      dir.Write("s.yaml", "grid:\n  select.min_area: [50, 60]\n  select.max_new: [1, 5000]\n"
                          "zip:\n  inhibition.margin: [0, 4, 8]\n  select.min_saliency: [0.1, 0.2, 0.3]\n"
                          "inputs:\n  - sequence: a\n");
  // Reading gives the lists as written, with their lines, and no cells.
  const SweepPlan plan = ReadSweepFile(file);
  EXPECT_TRUE(plan.cells.empty());
  ASSERT_EQ(plan.grid.size(), 2u);
  ASSERT_EQ(plan.zips.size(), 1u);
  EXPECT_EQ(plan.grid[1].where[1], dir.File("s.yaml") + ":3");
  EXPECT_EQ(plan.zips[0][1].values[2], "0.3");
  EXPECT_EQ(plan.groups, (std::vector<std::vector<int>>{{0}, {1}, {2, 3}}));
  EXPECT_EQ(SweepConfigurations(plan).size(), 2u * 2u * 3u);
  EXPECT_EQ(ExpandCells(plan).size(), 12u);
  // The check names the value out of range by its line.
  const std::string message = testing::ConfigErrorOf([&] { CheckSweepSettings(plan); });
  EXPECT_NE(message.find("s.yaml:3: grid.select.max_new: "), std::string::npos) << message;
}

TEST(SweepPlan, AKittiSequenceWithLabelsNeedsNoGtFolder) {
  const TempDir dir;
  const testing::KittiTestRig rig;
  const std::vector<cv::Mat> frames(2, cv::Mat(rig.size, CV_8UC3, cv::Scalar(50)));
  testing::WriteKittiTracking(dir, rig, frames, frames);
  const std::string file =
      dir.Write("s.yaml", "grid:\n  select.max_new: [1, 2]\ninputs:\n"
                          "  - sequence: training/image_02/0000\n");
  EXPECT_EQ(ReadSweepFile(file).inputs.size(), 1u);
  // Without its labels it has no ground truth for attend eval.
  std::filesystem::remove(dir.File("training/label_02/0000.txt"));
  const std::string message = testing::ConfigErrorOf([&] { ReadSweepFile(file); });
  EXPECT_NE(message.find("no objects.csv"), std::string::npos) << message;
}

TEST(SweepPlan, SlurmAndScoringAreReadThroughTheirFieldTables) {
  EXPECT_EQ(CheckFieldRanges(SlurmSettings(), SlurmSettings::Fields()), "");
  EXPECT_EQ(CheckFieldRanges(FixationScoring(), FixationScoring::Fields()), "");
  const TempDir dir;
  std::filesystem::create_directories(dir.File("fix"));
  const std::string inputs = "inputs:\n  - fixations: fix\n";
  const SweepPlan plan = ReadSweepFile(dir.Write(
      "s.yaml", inputs + "slurm: {partition: lab, cpus_per_task: 4}\n"
                         "score:\n  eval-fixations: {sigma: 12.5, baselines: [centre]}\n"));
  EXPECT_EQ(plan.command, SweepCommand::kSaliency);
  EXPECT_EQ(plan.slurm.partition, "lab");
  EXPECT_EQ(plan.slurm.cpus_per_task, 4);
  EXPECT_EQ(plan.slurm.throttle, 0);
  EXPECT_DOUBLE_EQ(plan.fixations.sigma, 12.5);
  EXPECT_EQ(plan.fixations.max_side, 640);
  EXPECT_EQ(plan.fixations.baselines, std::vector<std::string>{"centre"});
  const std::string throttle = testing::ConfigErrorOf([&] {
    ReadSweepFile(dir.Write("s.yaml", inputs + "slurm:\n  throttle: -1\n"));
  });
  EXPECT_NE(throttle.find("s.yaml:4: slurm.throttle: "), std::string::npos) << throttle;
  const std::string baseline = testing::ConfigErrorOf([&] {
    ReadSweepFile(dir.Write("s.yaml", inputs + "score:\n  eval-fixations:\n"
                                               "    baselines: [centre, centr]\n"));
  });
  EXPECT_NE(baseline.find("s.yaml:5: score.eval-fixations.baselines: 'centr' is not one of"),
            std::string::npos)
      << baseline;
  const std::string unknown = testing::ConfigErrorOf([&] {
    ReadSweepFile(dir.Write("s.yaml", inputs + "slurm:\n  partion: lab\n"));
  });
  EXPECT_NE(unknown.find("s.yaml:4: unknown key 'partion' in slurm (did you mean 'partition'?)"), std::string::npos) << unknown;
}

TEST(SweepInputs, EachSourceKindBecomesTheWordsOfItsCommand) {
  SweepInput input;
  input.kind = "left";
  input.path = "/v/l.mp4";
  input.right = "/v/r.mp4";
  EXPECT_EQ(SourceArguments(input),
            (std::vector<std::string>{"--left", "/v/l.mp4", "--right", "/v/r.mp4"}));
  input = SweepInput();
  input.kind = "side_by_side";
  input.path = "/v/sbs.mp4";
  EXPECT_EQ(SourceArguments(input), (std::vector<std::string>{"--side-by-side", "/v/sbs.mp4"}));
  input.kind = "scene";
  input.path = "/s/scenes/lab-0123";
  EXPECT_EQ(SourceArguments(input), (std::vector<std::string>{"--sequence", "/s/scenes/lab-0123"}));
  input.kind = "images";
  EXPECT_EQ(SourceArguments(input), (std::vector<std::string>{"--images", "/s/scenes/lab-0123"}));
}

// A scene of 2 small frames with one object, quick to render.
const char* const kTinyScene = R"(name: tiny
width: 48
height: 36
frames: 2
fps: 10
seed: 5
camera: {focal_px: 80, baseline_m: 0.125}
background: {depth: 5, colour: [110, 115, 120], texture: 15, texture_cell: 0.2}
objects:
  - id: 1
    shape: rectangle
    size: [0.3, 0.2]
    colour: [220, 30, 30]
    path: [{frame: 0, x: 10, y: 18, depth: 2}, {frame: 1, x: 30, y: 18, depth: 2}]
)";

TEST(SweepPlan, ASceneRendersWhenTheFolderIsPreparedNotWhenTheFileIsRead) {
  const TempDir dir;
  dir.Write("tiny.yaml", kTinyScene);
  const std::string file = dir.Write(
      "s.yaml", "set: {threads: 1}\ngrid:\n  select.max_new: [1, 2]\ninputs:\n  - scene: tiny.yaml\n");
  SweepReadOptions options;
  options.dir = dir.File("s");
  const SweepPlan plan = PlanSweep(file, options);
  ASSERT_EQ(plan.cells.size(), 2u);
  const std::string scene = plan.inputs[0].path;
  EXPECT_EQ(scene.rfind(dir.File("s/scenes/tiny-"), 0), 0u) << scene;
  EXPECT_FALSE(std::filesystem::exists(dir.File("s"))) << "planning wrote the sweep folder";

  std::vector<std::string> notes;
  const StoredSweep sweep = PrepareSweepFolder(plan, dir.File("s"), false, &notes);
  EXPECT_EQ(sweep.cells.size(), 2u);
  EXPECT_TRUE(std::filesystem::exists(scene + "/sequence.yaml")) << scene;
  EXPECT_TRUE(std::filesystem::exists(scene + "/gt/objects.csv")) << scene;
  const std::vector<std::vector<std::string>> commands = ReadCellCommands(sweep, sweep.cells[0]);
  ASSERT_EQ(commands.size(), 2u);
  EXPECT_NE(std::find(commands[0].begin(), commands[0].end(), scene), commands[0].end());
}

}  // namespace
}  // namespace attend
