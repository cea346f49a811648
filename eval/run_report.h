// The HTML report of `attend compare` and `attend report` (docs/COMPARE.md): one
// self-contained page (scripts and images inlined) that opens offline from a file.
#pragma once

#include <string>
#include <vector>

#include "eval/html_page.h"
#include "eval/run_comparison.h"

namespace attend {

struct ReportInput {
  std::vector<RunData> runs;               // runs[0] is the reference
  std::vector<RunComparison> comparisons;  // runs[i + 1] against runs[0]; empty for one run
  ChartLibrary chart;                      // Chart.js, inlined; the charts are left out without it
  std::string command_line;
  int thumbnail_frames = 3;   // frames shown side by side per comparison
  int thumbnail_width = 200;  // pixels
};

// The whole page. Reads the overlay and saliency dumps of the runs for the thumbnails; a
// missing one is shown as missing. A chart without data (no saliency dumps to compare, no
// timings, no targets) is left out rather than drawn empty.
std::string ReportHtml(const ReportInput& input);

// The frames of a comparison to show side by side: those with the lowest correlation
// coefficient; without saliency metrics, those with the fewest matched targets.
std::vector<int> MostDifferentFrames(const RunComparison& comparison, int count);

}  // namespace attend
