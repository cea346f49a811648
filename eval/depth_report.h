// The depth section of `attend compare` and `attend report` (docs/COMPARE.md): each run's
// targets' depth (eval/run_depth.h), the matched targets' differences, and a top view of the
// attended objects' tracks in metres for each run that has positions.
#pragma once

#include <string>
#include <vector>

#include "eval/run_comparison.h"

namespace attend {

// The top view of `frames`' targets as inline SVG: X (right) across, Z (forward) up, metres at
// equal scale, the camera at the origin; one polyline a target id in its overlay colour
// (TargetColour), labelled "#ID" at its last position; a dot every `dot_every` frames of the
// run (counted from its first frame; 0 picks about 12 over the run) whose opacity grows from
// 0.15 at the run's first frame to 1 at its last. The line breaks where the target was not
// seen for more than 3 frame steps. The plotted region holds the camera and the 2nd to 98th
// percentiles of the positions; `clipped` (when given) is set to the number of positions left
// outside. "" when no target has a position. `id` names the plot in the page.
std::string TopViewSvg(const std::vector<FrameRecord>& frames, const std::string& title,
                       const std::string& id, int dot_every = 0, int* clipped = nullptr);

// The section: "" when no run has a disparity or position. `labels`: each run's name in the
// page, in the order of `runs` (runs[0] the reference; comparisons[i] is runs[i + 1] against
// it).
std::string DepthSectionHtml(const std::vector<RunData>& runs,
                             const std::vector<RunComparison>& comparisons,
                             const std::vector<std::string>& labels);

}  // namespace attend
