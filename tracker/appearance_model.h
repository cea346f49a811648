// What the bounded mode (docs/TRACKING.md, "Modes" 8, 10, 11) learns of a target's looks
// besides its template: how distinctive each colour is of the target against its
// surroundings, and a grey model of its box matched by normalised cross-correlation (ZNCC).
// Not part of the API.
#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "tracker/roi_pyramid.h"
#include "tracker/target.h"
#include "tracker/tracker_options.h"

namespace attend {
namespace tracker_internal {

// The ZNCC of a target's grey model over an area of the frame: zncc(y, x) is that of the box
// moved by (x, y) - box_in_area pixels.
struct CorrelationMap {
  cv::Mat zncc;
  cv::Point box_in_area;  // the box's top left in the area

  // The correlation of the box moved by displacement d of level l; 0 where it was not
  // computed.
  double At(const cv::Point& d, int l) const {
    const int x = (d.x << l) + box_in_area.x, y = (d.y << l) + box_in_area.y;
    if (x < 0 || y < 0 || x >= zncc.cols || y >= zncc.rows) return 0.0;
    return zncc.at<float>(y, x);
  }
};

// Learns and matches the looks of targets; its buffers are reused from call to call, and no
// call reads what another left in them.
class AppearanceModel {
 public:
  explicit AppearanceModel(const TrackerOptions& options) : options_(options) {}

  // How distinctive each colour is of the target (its mask) against the rest of its ROI
  // outside its box, a histogram likelihood ratio f / (f + b) of the normalised counts,
  // blended into the previous table by `distinct_rate`. Colours the surroundings share count
  // little in the next frame's overlap; colours only the target has count wholly.
  void LearnDistinct(const Hierarchy& h, Target* target);

  // The grey model follows the found box by `appearance_rate`; the first box gives the model,
  // unless it is flat.
  void LearnGrey(const cv::Mat& grey, Target* target);

  // The ZNCC of the target's grey model, at its box's size, over `area` of `grey`; false when
  // there is no model or `area` cannot hold the box.
  bool Correlate(const cv::Mat& grey, const Target& target, const cv::Rect& area,
                 CorrelationMap* map);

  // The mean distinctiveness (LearnDistinct's table) of the frame's pixels in `box`; -1
  // without a table.
  double MeanDistinct(const TrackFrame& frame, const Target& target, const cv::Rect& box);

 private:
  TrackerOptions options_;
  cv::Mat model_, patch_, cylinder_;
  std::vector<float> fg_, bg_;  // LearnDistinct's histograms
};

}  // namespace tracker_internal
}  // namespace attend
