// The template search (thesis 4.2.3, eq. 4.5, 4.6): a target's template of one level shifted
// over the ROI's regular cells of that level, each displacement scored by its weighted overlap
// (and, in the bounded mode, by a motion prior and the grey appearance). The search returns
// what it found, its match with its overlap and correlation. Not part of the API.
#pragma once

#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

#include "tracker/appearance_model.h"
#include "tracker/roi_pyramid.h"
#include "tracker/target.h"
#include "tracker/template_update.h"

namespace attend {
namespace tracker_internal {

// A displacement of a target's template at one level.
struct Match {
  bool found = false;      // accepted
  int level = -1;          // of the pyramid; -1 when not found
  cv::Point displacement;  // cells of `level`
  double overlap = 0.0;    // the weighted overlap, 0..1
  // Scored with the appearance: the ZNCC at the best-scoring displacement, and whether any
  // displacement scored above 0 (`correlation` is then that one's, accepted or not).
  double correlation = 0.0;
  bool scored = false;
};

// How displacements are scored and accepted; the mode chooses (TrackerOptions).
struct SearchScoring {
  float t_colour = 30.f;     // T_c: a template vertex matches a ROI vertex below it (eq. 4.6)
  double min_overlap = 0.7;  // the weighted overlap that accepts, without the appearance
  // The motion prior: a displacement's score times a Gaussian of its distance to the previous
  // motion, sigma = motion_sigma times the box's mean side; 0: none.
  float motion_sigma = 0.f;
  // With the appearance (docs/TRACKING.md, "Modes" 10): a displacement scores the motion prior
  // times (1 - appearance_share) x overlap + appearance_share x max(0, ZNCC), accepted above
  // min_score (and with some colour overlap); nullptr: the overlap alone.
  const CorrelationMap* appearance = nullptr;
  double appearance_share = 0.0;
  double min_score = 0.0;
};

// One level's search data: the template over its occupied cells and the ROI's cells, both as
// planes of colour components, and the displacements in scan order.
struct SearchPlanes {
  cv::Rect occupied;  // absolute cells of the template's vertices (weight > 0)
  std::vector<float> colour[3];
  std::vector<int32_t> weight;  // fixed point, 1 = kWeightOne
  int64_t total = 0;
  std::vector<float> roi[3];  // the ROI cells, row by row; NaN where no regular vertex
  std::vector<cv::Point> displacements;
  std::vector<int> distance;  // per displacement of the range, in scan order
  std::vector<int> bucket;    // counting sort by distance

  // Loads template level `t` and the ROI cells `roi_cells` of `level` (whose cell (0, 0) is
  // absolute cell (ox, oy)). `distinct` (bounded mode; may be empty) scales each template
  // weight by how distinctive its colour is of the target (ColourBin()).
  void Load(const TemplateLevel& t, const BipLevel& level, const cv::Rect& roi_cells, int ox,
            int oy, const std::vector<float>& distinct);
  // The displacements of [dx0, dx1] x [dy0, dy1] ordered by squared distance to `prior`, those
  // at equal distance in scan order (rows, then columns): a stable counting sort.
  const std::vector<cv::Point>& Order(int dx0, int dx1, int dy0, int dy1, cv::Point prior);
};

// Searches templates; keeps its planes from call to call (no call reads what another left).
class TemplateSearch {
 public:
  // The best displacement of the target's template of level l over its ROI in `h` (within
  // `window`, in cells of l, when given), nearest the previous motion first so that the
  // nearest wins a tie; `found` when it is accepted.
  Match SearchLevel(const Target& target, const Hierarchy& h, int l, const cv::Rect* window,
                    const SearchScoring& scoring);

 private:
  SearchPlanes planes_;
};

}  // namespace tracker_internal
}  // namespace attend
