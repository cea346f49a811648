// The page of an OTB one-pass evaluation (`attend eval-tracking --otb`; docs/TRACKING.md, "The
// OTB evaluation"): the success and precision plots of all sequences and of each attribute, as
// the OTB toolkit draws them (mean curves, legends "name [AUC]" and "name [precision@20]"
// sorted by that number), the summary per tracker, and the scores and times per sequence. One
// self-contained HTML file: inline SVG, no script, no external file.
#pragma once

#include <string>

#include "eval/otb_results.h"

namespace attend {

// The page's HTML.
std::string OtbReportHtml(const OtbResults& results);

}  // namespace attend
