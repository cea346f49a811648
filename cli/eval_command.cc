// attend eval: the attention metrics of a run against ground truth (SPEC 3.2, 4).
#include <iostream>
#include <memory>
#include <string>

#include "app/evaluate_run.h"
#include "cli/commands.h"
#include "util/json_text.h"

namespace attend {

namespace {

struct EvalArguments {
  std::string run;
  std::string gt;
};

int Eval(const EvalArguments& args) {
  std::cout << JsonText(EvaluateRunFolder(args.run, args.gt)) << "\n";
  return 0;
}

}  // namespace

void AddEvalCommand(CLI::App& app, const std::string&, CommandAction* action) {
  auto args = std::make_shared<EvalArguments>();
  CLI::App* eval = app.add_subcommand(
      "eval",
      "Score a run against ground truth (SPEC 4): coverage, latency, revisits, identity "
      "switches and mean IoU of the attended objects; with dumped disparity maps and "
      "gt/disparity, their bad-pixel rates; with per-pixel truth (a rendered street scene's "
      "gt/classes), where attention lands (\"landing\": on objects, sky, ground). A run of a "
      "KITTI raw drive or tracking sequence is scored against the sequence's own labels and "
      "LiDAR scans (landing, and the targets' depth: depth_lidar). Prints one JSON object.");
  eval->add_option("RUN", args->run, "A run folder written by attend run")->required();
  eval->add_option("--gt", args->gt,
                   "Ground-truth folder holding objects.csv (default: the run's sequence "
                   "folder's gt/, or a KITTI sequence's labels)");
  eval->callback([args, action] { *action = [args] { return Eval(*args); }; });
}

ATTEND_COMMAND(70, "eval", AddEvalCommand);

}  // namespace attend
