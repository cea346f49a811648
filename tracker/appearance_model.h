// What the bounded mode (docs/TRACKING.md, "Modes" 8, 10, 11) learns of a target's looks
// besides its template: how distinctive each colour is of the target against its
// surroundings, and a grey model of its box matched by normalised cross-correlation (ZNCC).
// Not part of the API.
#pragma once

#include <algorithm>
#include <opencv2/core.hpp>
#include <vector>

#include "tracker/roi_pyramid.h"
#include "tracker/tracker.h"

namespace attend {
namespace tracker_internal {

struct Target;
struct TrackFrame;

// The grey standard deviation below which a target's appearance model is taken as flat.
inline constexpr double kMinAppearanceDeviation = 10.0;

// Bins of the HSV cylinder for the colour statistics: 32 units a side on each axis (S cos H and
// S sin H in [-255, 255], V in [0, 255]).
inline constexpr int kChromaBins = 16, kValueBins = 8;
inline constexpr int kColourBins = kChromaBins * kChromaBins * kValueBins;
inline int ColourBin(const float* f) {
  const int bx = std::clamp(static_cast<int>((f[0] + 256.f) / 32.f), 0, kChromaBins - 1);
  const int by = std::clamp(static_cast<int>((f[1] + 256.f) / 32.f), 0, kChromaBins - 1);
  const int bv = std::clamp(static_cast<int>(f[2] / 32.f), 0, kValueBins - 1);
  return (bx * kChromaBins + by) * kValueBins + bv;
}

// One target's looks. Empty in the thesis mode.
struct TargetAppearance {
  // Per colour bin, the share of the target's pixels among the target's and its surroundings'
  // (each normalised by its count); empty: every template weight counts wholly.
  std::vector<float> distinct;
  // The grey model of the box (CV_32FC1, the first box's size); empty for a flat first box.
  cv::Mat grey;
  bool judged = false;  // whether the first box was judged for texture
  // Running means of the correlation the model had, and of the mean distinctiveness of the
  // box (MeanDistinct), where the target was found.
  double typical_correlation = 0.0;
  double typical_distinct = 0.0;
};

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
