// What of a frame is background and no candidate for attention (select.background), and the
// proto-objects of depth grouping (select.group_depth). Per colour region of the frame's
// segmentation, in this order (the first that holds is its kind):
//   ground    stereo: at least select.ground_share of its measured pixels lie on the frame's
//             ground plane (stereo/ground_plane.h): the road, a floor;
//   no_depth  stereo: less than select.min_measured of its pixels have a measured disparity
//             (DisparityEstimator::measured), and it reaches the image's border: the sky, a
//             blank wall, a window's glare, whose disparity is the matcher's filled guess (a
//             plain object inside the frame is measured at its edges only, and stays a
//             candidate);
//   high      stereo, with a ground plane and a known baseline B: its measured pixels lie on
//             average more than select.max_height above the ground. A pixel at row v with
//             disparity d is B (1 / slope - (v - horizon) / d) metres above a ground of slope
//             `slope` (the camera's height is B / slope): tree tops and upper floors;
//   border    its pixels on the image's outer rows and columns are at least select.border_share
//             of the border's pixels: the boundary prior of the saliency literature (Wei et
//             al., ECCV 2012: background touches the frame, objects seldom fill much of its
//             edge); the sky, the road and a wall on a monocular frame too;
//   large     larger than select.max_area_fraction of the image.
// Background regions take no part in candidates (their saliency is set to 0 for the
// selection), in seeds or in targets; a found target with more than half of its mask on them
// is released ("background"). A monocular frame has the border and large rules only.
//
// Each region's depth is the mean of its measured disparities (NaN with fewer than
// min_measured of its pixels measured): object seeds grow by it (GroupByDepth).
#pragma once

#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

#include "pyramid/regions.h"
#include "semiattentive/select_options.h"
#include "stereo/ground_plane.h"

namespace attend {

enum class BackgroundKind : uint8_t { kNone, kGround, kNoDepth, kHigh, kBorder, kLarge };

struct SceneRegions {
  std::vector<BackgroundKind> kind;  // per colour region
  std::vector<float> disparity;      // per colour region: mean measured disparity, or NaN
  // CV_8UC1: the BackgroundKind of each pixel's region, 0 (kNone) off the background; a mask
  // of the background as it is.
  cv::Mat mask;
  GroundPlane ground;                // the frame's (not valid on a monocular frame)
};

// "ground", "no_depth", "high", "border", "large" ("" for kNone).
const char* BackgroundKindName(BackgroundKind kind);

class SceneAnalysis {
 public:
  explicit SceneAnalysis(const SelectOptions& options) : options_(options) {}

  bool enabled() const { return options_.background; }
  // The stereo pair's baseline in metres (0: unknown, no `high` rule).
  void set_baseline(double baseline_m) { baseline_m_ = baseline_m; }
  // Analyses a frame: its `segmentation` and, on a stereo frame, its `disparity` (CV_32FC1) and
  // where it was `measured` (CV_8UC1, 255); both empty on a monocular frame.
  void Analyse(const Segmentation& segmentation, const cv::Mat& disparity,
               const cv::Mat& measured);
  // The same with the frame's ground plane fitted already (FitGroundPlane of `disparity` over
  // `measured`; the frame context's, which the disparity feature used).
  void Analyse(const Segmentation& segmentation, const cv::Mat& disparity, const cv::Mat& measured,
               const GroundPlane& ground);
  const SceneRegions& regions() const { return regions_; }
  // The share of the pixels of `mask` (CV_8UC1, frame size) within `box` that are background.
  double BackgroundShare(const cv::Mat& mask, const cv::Rect& box) const;
  // `saliency` (CV_32FC1, frame size) with the background's pixels at 0: the analysis's buffer,
  // valid until it is called again.
  const cv::Mat& WithoutBackground(const cv::Mat& saliency);
  // The width in metres of colour region `region` at its depth (its box's width times
  // baseline / disparity); NaN without a depth or a baseline.
  double WidthM(const Segmentation& segmentation, int region) const;
  // The widest skin a person shows (a face, hands, bare arms spread): a skin-coloured region
  // wider than this is no one's skin (AttentionStage's skin test).
  static constexpr double kMaxSkinWidthM = 0.8;
  // Marks the background's colour regions in `taken` (one flag per region).
  void MarkTaken(std::vector<uint8_t>* taken) const;
  // Whether a found target (its `mask` within `box`) has slid onto the background: more than
  // kMovedOnShare of its mask on it for kMovedOnFrames frames in a row, `frames` counting them
  // (a region's kind flickers from frame to frame where it is near a rule's bound).
  bool OnBackground(const cv::Mat& mask, const cv::Rect& box, int* frames) const;
  static constexpr double kMovedOnShare = 0.7;
  static constexpr int kMovedOnFrames = 3;
  // Object seeds: grows `members` (a seed's colour regions, the best first; `area` their
  // pixels) region by region outwards with the neighbours whose depth lies within
  // select.group_depth of the best region's, that are not `taken` nor background, while the
  // seed stays within `max_area` pixels. Nothing without a depth for the best region.
  void GroupByDepth(const Segmentation& segmentation, const std::vector<uint8_t>& taken,
                    double max_area, std::vector<int>* members, double* area) const;

 private:
  SelectOptions options_;
  double baseline_m_ = 0.0;
  SceneRegions regions_;
  cv::Mat without_;  // WithoutBackground's
};

}  // namespace attend
