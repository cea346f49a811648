// The target's pixels from a match (thesis 4.2.4): the regions of the matched ROI vertices, then
// those of their neighbours of similar colour, painted into the target's mask. Not part of the
// API.
#pragma once

#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

#include "tracker/roi_pyramid.h"
#include "tracker/template_update.h"

namespace attend {
namespace tracker_internal {

// First stage of 4.2.4: the regions of the ROI vertices under the template `t` of level l moved
// by `displacement` (cells of l) whose colour is within `t_colour` (T_c) of the template's are
// the target's: they are marked in `in_target`.
void MarkMatched(const TemplateLevel& t, const Hierarchy& h, int l, cv::Point displacement,
                 float t_colour, std::vector<uint8_t>* in_target);

// Second stage of 4.2.4: the regions of neighbours (regular and virtual) of the target's
// regular vertices in `roi` that are within `t_refine` (T_cr) of them join the target. One
// pass, over the target as the first stage left it.
void Refine(const Hierarchy& h, const cv::Rect& roi, float t_refine,
            std::vector<uint8_t>* in_target);

// Sets the target's pixels in `roi` in `mask` (made `frame_size`, 0 elsewhere).
void PaintTarget(const Hierarchy& h, const std::vector<uint8_t>& in_target, const cv::Rect& roi,
                 cv::Size frame_size, cv::Mat* mask);

}  // namespace tracker_internal
}  // namespace attend
