// Candidates of the attention stage (thesis 5.1.2, SPEC 2.4): the inhibited saliency map is
// segmented into regions of homogeneous saliency (a BIP over the map, T_max
// select.saliency_t_max); a region whose mean inhibited saliency is at least
// select.min_saliency and whose area is at least select.min_area is a candidate, ranked by
// mean saliency times area.
#pragma once

#include <map>
#include <opencv2/core.hpp>
#include <utility>
#include <vector>

#include "features/feature_map.h"
#include "pyramid/bip.h"
#include "pyramid/regions.h"
#include "semiattentive/select_options.h"

namespace attend {

// The saliency regions of a frame and, per region, its inhibited saliency's sum, its area, its
// most salient pixel and its bounds.
struct Candidates {
  cv::Mat labels;  // CV_32SC1: the saliency region of each pixel, -1: none
  std::vector<double> sum;
  std::vector<int> area;
  std::vector<cv::Point> peak;
  std::vector<float> peak_value;
  std::vector<cv::Point> low, high;  // the extreme pixels' coordinates (inclusive)
  // The candidates, (mean x area, region), best first.
  std::vector<std::pair<double, int>> ranked;
  // The bounding box of saliency region `region`.
  cv::Rect Box(int region) const { return cv::Rect(low[region], high[region] + cv::Point(1, 1)); }
};

// Finds the candidates of each frame; keeps the BIP builder, whose levels it borrows from the
// shared pool only while it segments.
class CandidateFinder {
 public:
  // `pool`: where the saliency map's pyramid borrows its levels (pyramid/bip.h); nullptr: a
  // pool of its own.
  explicit CandidateFinder(const SelectOptions& options, BipPool* pool = nullptr);
  // The candidates of `inhibited` (CV_32FC1, 0..1).
  Candidates Find(const cv::Mat& inhibited);

 private:
  float min_saliency_;
  int min_area_;
  float t_max_;
  BipBuilder builder_;
  cv::Mat scaled_row_, features_;  // kept from frame to frame (Find)
};

// Ranks `candidates` (best first) as the order of attention says (SelectOptions::order,
// proximity, faces_first): `focus` is where attention is (the last target started; nullptr:
// nowhere yet, no proximity), `detections` the frame's (those labelled "face" count for
// faces_first). Ties keep the regions' order.
void RankCandidates(const SelectOptions& options, const cv::Point2d* focus,
                    const std::vector<Detection>& detections, cv::Size image,
                    Candidates* candidates);

// The colour regions under each candidate and those a target holds.
struct CandidateRegions {
  std::vector<std::map<int, int>> overlaps;  // per ranked candidate: colour region -> pixels
  std::vector<uint8_t> taken;                // per colour region: `covered` marks a pixel of it
};
// The colour regions of `segmentation` under each of `candidates`' ranked candidates, and those
// that `covered` (CV_8UC1, the active targets' pixels) marks.
CandidateRegions RegionsUnder(const Candidates& candidates, const Segmentation& segmentation,
                              const cv::Mat& covered);

}  // namespace attend
