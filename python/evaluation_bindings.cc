// attend.eval_run, eval_fixations and compare (python/bindings.h).
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <string>
#include <vector>

#include "app/evaluate_fixations.h"
#include "app/evaluate_run.h"
#include "app/write_report.h"
#include "python/bindings.h"
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

}  // namespace

void RegisterEvaluation(py::module_& m) {
  m.def("eval_run", &EvalRun);
  m.def("eval_fixations", &EvalFixations);
  m.def("compare", &Compare);
}

}  // namespace attend::python
