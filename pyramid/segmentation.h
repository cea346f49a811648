// BIP colour segmentation (thesis 3.3.1): the roots' receptive fields are the regions.
#pragma once

#include <memory>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "colour/colour.h"
#include "pyramid/bip.h"
#include "pyramid/regions.h"
#include "util/option_fields.h"

namespace attend {

struct SegmentationOptions {
  // T_max of the threshold schedule T(l) = T_max a(l) (eq. 3.1), in HSV-cylinder units
  // (S and V in [0, 255]).
  float t_max = 40.f;
  // Regions smaller than this many pixels are merged into their most similar neighbour
  // (smallest first), as in the thesis's comparison of segmentations (3.3.2: 20 pixels for
  // every method). 0 keeps the pyramid's roots as they are.
  int min_region_area = 20;
  // Not in the thesis: after the small-region merge, adjacent regions merge when their mean
  // colours differ by at most merge_spread times the root mean square of their colour spreads
  // (closest pairs first; docs/PYRAMID.md, "Merging by spread"). It joins the pieces into
  // which the colour threshold cuts a textured surface. 0 keeps the thesis's regions, which
  // the attention loop uses; `attend segment` defaults to 1 with t_max 50
  // (configs/segment.yaml), its best measured setting.
  float merge_spread = 0.f;
  BipOptions bip;

  // "" when valid; otherwise names the field and the broken constraint.
  std::string Check() const;
  // The fields (util/option_fields.h), which Check and the configuration apply.
  static const OptionFields<SegmentationOptions>& Fields();
};

// Segments images; keeps its scratch buffers between calls and borrows the pyramid's from a
// BipPool, so one Segmenter per stream of frames allocates (almost) nothing after the first
// frame.
class Segmenter {
 public:
  // `pool`: the pyramid's pool, as for BipBuilder (pyramid/bip.h); nullptr: its own.
  explicit Segmenter(SegmentationOptions options = {}, BipPool* pool = nullptr);
  ~Segmenter();
  Segmenter(const Segmenter&) = delete;
  Segmenter& operator=(const Segmenter&) = delete;

  // Segments an 8-bit BGR image.
  void Segment(const cv::Mat& bgr, Segmentation* out);
  // Segments from a precomputed HSV cylinder image (colour/colour.h), optionally within a mask.
  void SegmentCylinder(const cv::Mat& cylinder, Segmentation* out, const cv::Mat& mask = cv::Mat());

  // The pyramid of the last call, until ReleasePyramid().
  const Bip& bip() const { return builder_.bip(); }
  // Gives the pyramid's levels back to the pool (pyramid/bip.h) for other builds; the
  // segmentation made from it stays valid.
  void ReleasePyramid() { builder_.Release(); }
  const SegmentationOptions& options() const { return options_; }

 private:
  SegmentationOptions options_;
  HsvSimilarity policy_;
  BipBuilder builder_;
  cv::Mat cylinder_;
  // Scratch buffers of the region statistics and the small-region merge, kept between calls.
  struct Workspace;
  std::unique_ptr<Workspace> workspace_;
};

// Paints each region with a distinct colour (hashing its index), black outside the mask.
cv::Mat FalseColour(const cv::Mat& labels);

// Paints each region with its mean colour (8-bit BGR from the region's mean cylinder colour).
cv::Mat MeanColourImage(const cv::Mat& labels, const std::vector<RegionStats>& regions);

}  // namespace attend
