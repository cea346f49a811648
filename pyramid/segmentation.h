// BIP colour segmentation (thesis 3.3.1): the roots' receptive fields are the regions.
#pragma once

#include <boost/graph/adjacency_list.hpp>
#include <memory>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "colour/colour.h"
#include "pyramid/bip.h"

namespace attend {

struct SegmentationOptions {
  // T_max of the threshold schedule T(l) = T_max a(l) (eq. 3.1), in HSV-cylinder units
  // (S and V in [0, 255]).
  float t_max = 40.f;
  // Regions smaller than this many pixels are merged into their most similar neighbour
  // (smallest first), as in the thesis's comparison of segmentations (3.3.2: 20 pixels for
  // every method). 0 keeps the pyramid's roots as they are.
  int min_region_area = 20;
  BipOptions bip;

  // "" when valid; otherwise names the field and the broken constraint.
  std::string Check() const;
};

// Statistics of one region, over its pixels.
struct RegionStats {
  int area = 0;            // pixels
  CylinderColour colour;   // mean cylinder colour (the root's feature)
  float saturation = 0.f;  // mean of the pixels' S, [0, 255]
  float intensity = 0.f;   // mean of the pixels' V, [0, 255]
  cv::Rect bbox;
  // PL_i of eq. 5.1: 4-neighbour pixel edges between this region and other regions; the image
  // border and pixels outside the mask do not count.
  int perimeter = 0;
};

// The region adjacency graph: one vertex per region (same index as the label), an edge per
// pair of regions sharing at least one 4-neighbour pixel edge, weighted by their number
// (pl_ij of eq. 5.1).
struct RegionBoundary {
  int length = 0;
};
// Edges are kept in a vector (not Boost's default list), so building the graph of a frame
// costs a few allocations rather than one per edge.
using RegionGraph =
    boost::adjacency_list<boost::vecS, boost::vecS, boost::undirectedS, boost::no_property,
                          RegionBoundary, boost::no_property, boost::vecS>;

struct Segmentation {
  // CV_32SC1: region index per pixel, -1 outside the mask. Every region is 8-connected.
  cv::Mat labels;
  std::vector<RegionStats> regions;
  RegionGraph graph;
  int pyramid_levels = 0;     // height of the hierarchy
  double milliseconds = 0.0;  // building the pyramid and labelling, not conversions or I/O
};

// Segments images; keeps the pyramid and all scratch buffers between calls, so one Segmenter
// per stream of frames allocates (almost) nothing after the first frame.
class Segmenter {
 public:
  explicit Segmenter(SegmentationOptions options = {});
  ~Segmenter();
  Segmenter(const Segmenter&) = delete;
  Segmenter& operator=(const Segmenter&) = delete;

  // Segments an 8-bit BGR image.
  void Segment(const cv::Mat& bgr, Segmentation* out);
  // Segments from a precomputed HSV cylinder image (colour/colour.h), optionally within a mask.
  void SegmentCylinder(const cv::Mat& cylinder, Segmentation* out, const cv::Mat& mask = cv::Mat());

  // The pyramid of the last call.
  const Bip& bip() const { return builder_.bip(); }
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
