// The HTML report of `attend compare` and `attend report` (docs/COMPARE.md): one
// self-contained page (scripts and images inlined) that opens offline from a file.
#pragma once

#include <string>
#include <vector>

#include "eval/run_comparison.h"

namespace attend {

struct ReportInput {
  std::vector<RunData> runs;               // runs[0] is the reference
  std::vector<RunComparison> comparisons;  // runs[i + 1] against runs[0]; empty for one run
  std::string chart_js;                    // the Chart.js library's source; "" when not found
  std::string chart_js_source;             // where it was read, or where it was looked for
  std::string command_line;
  int thumbnail_frames = 3;   // frames shown side by side per comparison
  int thumbnail_width = 200;  // pixels
};

// Where the Chart.js library of Debian's libjs-chart.js is, "" when it is not installed.
std::string FindChartJs();

// The whole page. Reads the overlay and saliency dumps of the runs for the thumbnails; a
// missing one is shown as missing.
std::string ReportHtml(const ReportInput& input);

// The frames of a comparison to show side by side: those with the lowest correlation
// coefficient; without saliency metrics, those with the fewest matched targets.
std::vector<int> MostDifferentFrames(const RunComparison& comparison, int count);

// RFC 4648 base64 of `bytes`.
std::string Base64(const std::vector<unsigned char>& bytes);

}  // namespace attend
