// The controller of `attend compare` and `attend report` (SPEC 3.2, 4; docs/COMPARE.md): loads
// the runs, compares each with the first, and writes OUT/summary.json and a self-contained
// OUT/report.html. The commands only parse their arguments.
#pragma once

#include <string>
#include <vector>

namespace attend {

struct ReportRequest {
  std::vector<std::string> runs;  // run folders; the first is A, the others are compared with it
  std::string out;
  // gt/ folders (holding objects.csv) to score the runs against: one for every run, or one a
  // run; none: each run's sequence folder's gt/ where it has one.
  std::vector<std::string> gt;
  bool overwrite = false;    // replace an earlier report in `out`
  std::string command_line;  // recorded in summary.json and the report
};

struct ReportResult {
  std::string html;                // the report's path
  std::vector<std::string> notes;  // "B vs A: ..." for each comparison's notes
};

// InputError for a run folder that cannot be read or a gt/ folder without objects.csv;
// ConfigError for a number of gt/ folders that is neither 1 nor the number of runs;
// OutputError when `out` cannot be prepared
// or written (each file is written whole or not at all).
ReportResult WriteReport(const ReportRequest& request);

}  // namespace attend
