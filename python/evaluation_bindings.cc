// attend.eval_run, eval_fixations and compare, and the checks of attend.read_run
// (python/bindings.h).
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <system_error>
#include <vector>

#include "app/evaluate_fixations.h"
#include "app/evaluate_run.h"
#include "app/write_report.h"
#include "eval/run_comparison.h"
#include "io/frame_record.h"
#include "python/bindings.h"
#include "util/error.h"
#include "util/json_text.h"

namespace attend::python {

namespace {

std::string EvalRun(const std::string& run, const std::string& gt) {
  nlohmann::ordered_json report;
  {
    const py::gil_scoped_release release;
    report = EvaluateRunFolder(run, gt);
  }
  return JsonText(report, -1);
}

py::dict EvalFixations(const std::vector<std::string>& maps, const std::string& dataset,
                       const std::string& out, const std::vector<std::string>& baselines,
                       double sigma, int max_side, int skip, int first) {
  EvalFixationsRequest request;
  request.maps = maps;
  request.dataset = dataset;
  request.out = out;
  request.baselines = baselines;
  request.sigma = sigma;
  request.max_side = max_side;
  request.skip = skip;
  request.first = first;
  request.quiet = true;
  request.command_line = "python: attend.eval_fixations";
  FixationEvaluation evaluation;
  {
    const py::gil_scoped_release release;
    evaluation = EvaluateFixations(request, {});
  }
  py::dict result;
  result["table"] = evaluation.table;
  result["failed"] = evaluation.failed;
  return result;
}

std::string Compare(const std::vector<std::string>& runs, const std::string& out, bool overwrite,
                    const std::vector<std::string>& gt) {
  ReportRequest request;
  request.runs = runs;
  request.out = out;
  request.gt = gt;
  request.overwrite = overwrite;
  request.command_line = "python: attend.compare";
  const py::gil_scoped_release release;
  return WriteReport(request).html;
}

// InputError unless `path` is a regular file (a folder, a fifo or a device is not read: a fifo
// would block, /dev/zero would be read for ever).
void CheckRegularFile(const std::string& path) {
  std::error_code error;
  if (std::filesystem::is_regular_file(path, error)) return;
  const bool folder = std::filesystem::is_directory(path, error);
  throw InputError(path + ": " + (folder ? "is a folder, not a file"
                                         : "is not a regular file (a fifo, a device, a socket)"));
}

// RUN/frames.jsonl checked as `attend eval` and `attend compare` read it (ReadFrameRecords:
// the same refusals, word for word); InputError naming the file and line. Returns the number
// of records.
size_t CheckFrameRecords(const std::string& path) {
  const py::gil_scoped_release release;
  CheckRegularFile(path);
  return ReadFrameRecords(path).size();
}

// RUN/config.yaml checked as `attend compare` reads it (FlattenConfigFile: YAML within
// ParamBlock's bounds, no duplicate keys); InputError naming the file.
void CheckRunConfig(const std::string& path) {
  const py::gil_scoped_release release;
  CheckRegularFile(path);
  FlattenConfigFile(path);
}

}  // namespace

void RegisterEvaluation(py::module_& m) {
  m.def("eval_run", &EvalRun);
  m.def("eval_fixations", &EvalFixations);
  m.def("compare", &Compare);
  m.def("_check_regular_file", &CheckRegularFile);
  m.def("_check_frame_records", &CheckFrameRecords);
  m.def("_check_run_config", &CheckRunConfig);
}

}  // namespace attend::python
