// attend compare and attend report: what changed between runs, and the HTML report
// (SPEC 3.2, 4; docs/COMPARE.md).
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "app/write_report.h"
#include "cli/commands.h"

namespace attend {

namespace {

struct CompareArguments {
  std::vector<std::string> runs;
  std::string out;
  std::vector<std::string> gt;
  bool overwrite = false;
};

int Compare(const CompareArguments& args, const std::string& command_line) {
  const ReportResult result = WriteReport({args.runs, args.out, args.gt, args.overwrite, command_line});
  for (const std::string& note : result.notes) std::cerr << "attend: note: " << note << "\n";
  std::cout << result.html << "\n";
  return 0;
}

}  // namespace

void AddCompareCommand(CLI::App& app, const std::string& command_line, CommandAction* action) {
  auto args = std::make_shared<CompareArguments>();
  CLI::App* compare = app.add_subcommand(
      "compare",
      "Compare runs with the first one (SPEC 4): configuration differences, saliency CC, SIM "
      "and KL per frame, matched targets and attention order, per-stage timings. Writes "
      "DIR/summary.json and a self-contained DIR/report.html (docs/COMPARE.md).");
  compare->add_option("RUN", args->runs, "Run folders written by attend run; the first is A")
      ->required()
      ->expected(2, -1);
  compare->add_option("--out", args->out, "Output folder for summary.json and report.html")
      ->required();
  compare->add_option("--gt", args->gt,
                      "Ground-truth folder holding objects.csv, for runs whose source has no gt/ "
                      "(a video): once for every run, or once a run in their order");
  compare->add_flag("--overwrite", args->overwrite, "Replace an earlier report in DIR");
  compare->callback([args, action, command_line] {
    *action = [args, command_line] { return Compare(*args, command_line); };
  });
}

void AddReportCommand(CLI::App& app, const std::string& command_line, CommandAction* action) {
  auto args = std::make_shared<CompareArguments>();
  CLI::App* report = app.add_subcommand(
      "report",
      "The HTML report of one run: per-stage timings, targets per frame, overlay and saliency "
      "thumbnails, the targets in attention order. Writes DIR/summary.json and DIR/report.html.");
  report->add_option("RUN", args->runs, "A run folder written by attend run")
      ->required()
      ->expected(1);
  report->add_option("--out", args->out, "Output folder for summary.json and report.html")
      ->required();
  report->add_option("--gt", args->gt,
                     "Ground-truth folder holding objects.csv, for a run whose source has no gt/ "
                     "(a video)")
      ->expected(1);
  report->add_flag("--overwrite", args->overwrite, "Replace an earlier report in DIR");
  report->callback([args, action, command_line] {
    *action = [args, command_line] { return Compare(*args, command_line); };
  });
}

ATTEND_COMMAND(90, "compare", AddCompareCommand);

ATTEND_COMMAND(100, "report", AddReportCommand);

}  // namespace attend
