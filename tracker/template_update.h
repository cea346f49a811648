// A target's template (thesis 4.2.1) and its update (4.2.5-4.2.7): per level of the pyramid,
// the homogeneous cells of the target with their colour, area and a weight that is 1 where the
// target was last seen and decays by the forgetting constant alpha elsewhere (eq. 4.7, 4.8).
// Not part of the API.
#pragma once

#include <algorithm>
#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

#include "tracker/roi_pyramid.h"

namespace attend {
namespace tracker_internal {

// One level of a template: a window of absolute cells with each vertex's colour, area and
// weight (weight 0: no vertex).
struct TemplateLevel {
  cv::Rect cells;  // absolute cell coordinates of the window
  std::vector<float> colour;
  std::vector<int> area;
  std::vector<float> weight;

  size_t Index(int x, int y) const {
    return static_cast<size_t>(y - cells.y) * cells.width + (x - cells.x);
  }
  double TotalArea() const {
    double total = 0.0;
    for (size_t i = 0; i < weight.size(); ++i) total += weight[i] > 0.f ? area[i] : 0;
    return total;
  }
  bool Empty() const {
    return std::none_of(weight.begin(), weight.end(), [](float w) { return w > 0.f; });
  }
};

// The template of a target from the regular cells of `h` in the target's regions (eq. 4.7).
// `in_target` says whether a region is the target's; `keep` limits it to a box (absolute
// pixels). Cells of the old template that the new target does not cover stay with their
// weight reduced by `alpha` (eq. 4.8), shifted by `shift` pixels. `pyramid_levels` is the
// height of the whole pyramid over the union of the ROIs, of which `h` may be a lower part:
// above the part's own levels, old cells only move and decay. Empty top levels are dropped.
std::vector<TemplateLevel> MakeTemplate(const Hierarchy& h, const std::vector<uint8_t>& in_target,
                                        const cv::Rect& keep, const std::vector<TemplateLevel>* old,
                                        cv::Point shift, int pyramid_levels, float alpha);

// The working level (eq. 4.4): the highest level whose template area exceeds `working_area`
// (T_A) of level 0's; -1 for an empty template.
int WorkingLevel(const std::vector<TemplateLevel>& levels, float working_area);

// A target not found (4.2.7): every weight decays by `alpha`, and levels left empty at the top
// are dropped (an empty template is a lost target).
void Decay(float alpha, std::vector<TemplateLevel>* levels);

// The template moved by `shift` pixels (each level by the shift in its cells, rounded).
void MoveTemplate(cv::Point shift, std::vector<TemplateLevel>* levels);

}  // namespace tracker_internal
}  // namespace attend
