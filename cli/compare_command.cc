// attend compare and attend report: what changed between runs, and the HTML report
// (SPEC 3.2, 4; docs/COMPARE.md).
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli/commands.h"
#include "eval/run_comparison.h"
#include "eval/run_report.h"
#include "util/error.h"
#include "util/output_folder.h"
#include "util/json_text.h"

namespace attend {

namespace {

namespace fs = std::filesystem;

struct CompareArguments {
  std::vector<std::string> runs;
  std::string out;
  bool overwrite = false;
};

nlohmann::ordered_json RunJson(const RunData& run) {
  nlohmann::ordered_json timings = nlohmann::ordered_json::object();
  for (const auto& [stage, ms] : run.mean_timings_ms) timings[stage] = ms;
  return {{"dir", run.dir},
          {"sequence", run.sequence},
          {"frames", run.frames.size()},
          {"interrupted", run.interrupted},
          {"timings_ms", timings},
          {"ground_truth", run.ground_truth.empty() ? nlohmann::ordered_json()
                                                    : nlohmann::ordered_json(run.ground_truth)},
          {"attention", AttentionToJson(run.attention)},
          {"targets", TargetsToJson(SummariseTargets(run.frames))}};
}

void WriteText(const fs::path& path, const std::string& text) {
  const fs::path partial = path.string() + ".partial";
  {
    std::ofstream out(partial, std::ios::binary);
    out << text;
    if (!out) throw OutputError(path.string() + ": cannot write");
  }
  std::error_code error;
  fs::rename(partial, path, error);
  if (error) throw OutputError(path.string() + ": cannot write (" + error.message() + ")");
}

int Compare(const CompareArguments& args, const std::string& command_line) {
  ReportInput input;
  input.command_line = command_line;
  for (const std::string& run : args.runs) input.runs.push_back(LoadRun(run));
  for (std::size_t i = 1; i < input.runs.size(); ++i) {
    input.comparisons.push_back(CompareRuns(input.runs[0], input.runs[i]));
  }
  const std::string chart_js = FindChartJs();
  if (chart_js.empty()) {
    input.chart_js_source = "looked for /usr/share/javascript/chart.js/chart.min.js";
  } else {
    std::ifstream in(chart_js, std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    input.chart_js = text.str();
    input.chart_js_source = chart_js;
  }

  PrepareOutputFolder(args.out, args.overwrite,
                      {"report", {"summary.json", "report.html"}, [](const std::string& folder) {
                         std::error_code error;
                         return fs::is_regular_file(fs::path(folder) / "report.html", error);
                       }});
  nlohmann::ordered_json runs = nlohmann::ordered_json::array();
  for (const RunData& run : input.runs) runs.push_back(RunJson(run));
  nlohmann::ordered_json comparisons = nlohmann::ordered_json::array();
  for (const RunComparison& c : input.comparisons) comparisons.push_back(ComparisonToJson(c));
  const nlohmann::ordered_json summary = {
      {"command", command_line},
      {"runs", runs},
      {"comparisons", comparisons},
      {"report", "report.html"},
      {"chart_js", chart_js.empty() ? nlohmann::ordered_json() : nlohmann::ordered_json(chart_js)}};
  const fs::path out(args.out);
  WriteText(out / "summary.json", JsonText(summary, 2) + "\n");
  WriteText(out / "report.html", ReportHtml(input));
  for (const RunComparison& c : input.comparisons) {
    for (const std::string& note : c.notes) {
      std::cerr << "attend: note: " << c.run_b << " vs " << c.run_a << ": " << note << "\n";
    }
  }
  std::cout << (out / "report.html").string() << "\n";
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
  report->add_flag("--overwrite", args->overwrite, "Replace an earlier report in DIR");
  report->callback([args, action, command_line] {
    *action = [args, command_line] { return Compare(*args, command_line); };
  });
}

}  // namespace attend
