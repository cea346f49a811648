#include "app/write_report.h"

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <system_error>

#include "eval/run_comparison.h"
#include "eval/run_depth.h"
#include "eval/run_report.h"
#include "util/error.h"
#include "util/json_text.h"
#include "util/output_folder.h"

namespace attend {

namespace {

namespace fs = std::filesystem;

nlohmann::ordered_json RunJson(const RunData& run) {
  const RunDepth depth = SummariseDepth(run.frames);
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
          {"depth", depth.any() ? RunDepthToJson(depth) : nlohmann::ordered_json()},
          {"targets", TargetsToJson(SummariseTargets(run.frames))}};
}

}  // namespace

ReportResult WriteReport(const ReportRequest& request) {
  const std::string& command_line = request.command_line;
  ReportInput input;
  input.command_line = command_line;
  if (!request.gt.empty() && request.gt.size() != 1 && request.gt.size() != request.runs.size()) {
    throw ConfigError("--gt given " + std::to_string(request.gt.size()) + " times for " +
                      std::to_string(request.runs.size()) +
                      " runs: give one gt/ folder for every run, or one a run in their order");
  }
  for (std::size_t i = 0; i < request.runs.size(); ++i) {
    const std::string gt = request.gt.empty()      ? std::string()
                           : request.gt.size() == 1 ? request.gt[0]
                                                    : request.gt[i];
    input.runs.push_back(LoadRun(request.runs[i], gt));
  }
  for (std::size_t i = 1; i < input.runs.size(); ++i) {
    input.comparisons.push_back(CompareRuns(input.runs[0], input.runs[i]));
  }
  input.chart = LoadChartLibrary();

  const FolderLock lock = PrepareOutputFolder(request.out, request.overwrite,
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
      {"chart_js", input.chart.found() ? nlohmann::ordered_json(input.chart.path)
                                       : nlohmann::ordered_json()}};
  const fs::path out(request.out);
  ReplaceFileText((out / "summary.json").string(), JsonText(summary, 2) + "\n");
  ReplaceFileText((out / "report.html").string(), ReportHtml(input));
  ReportResult result;
  result.html = (out / "report.html").string();
  for (const RunComparison& c : input.comparisons) {
    for (const std::string& note : c.notes) {
      result.notes.push_back(c.run_b + " vs " + c.run_a + ": " + note);
    }
  }
  return result;
}

}  // namespace attend
