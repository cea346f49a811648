// The result of a colour segmentation (pyramid/segmentation.h), as plain data: the label image,
// each region's statistics and the region adjacency graph. It is what feature plugins see of
// the segmentation (features/frame_context.h), so its layout does not depend on how the
// pyramid that made it is built.
#pragma once

#include <boost/graph/adjacency_list.hpp>
#include <opencv2/core.hpp>
#include <vector>

#include "colour/colour.h"

namespace attend {

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

}  // namespace attend
