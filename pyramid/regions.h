// The result of a colour segmentation (pyramid/segmentation.h), as plain data: the label image,
// each region's statistics and the region adjacency graph. It is what feature plugins see of
// the segmentation (features/frame_context.h), so its layout does not depend on how the
// pyramid that made it is built.
#pragma once

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

// One edge of the region adjacency graph: regions a < b share `length` 4-neighbour pixel edges
// (pl_ab of eq. 5.1).
struct RegionBoundary {
  int a = 0;
  int b = 0;
  int length = 0;
};

// The region adjacency graph as plain data: one vertex per region (same index as the label),
// an edge per pair of regions sharing at least one 4-neighbour pixel edge. Each region's
// neighbours are listed in the order of `boundaries`.
struct RegionAdjacency {
  std::vector<RegionBoundary> boundaries;
  std::vector<int> offsets;     // per region, and one past the last: where its neighbours start
  std::vector<int> neighbours;  // region r's: neighbours[offsets[r]] .. [offsets[r + 1] - 1]

  int num_regions() const { return offsets.empty() ? 0 : static_cast<int>(offsets.size()) - 1; }
  const int* NeighboursBegin(int region) const { return neighbours.data() + offsets[region]; }
  const int* NeighboursEnd(int region) const { return neighbours.data() + offsets[region + 1]; }
};

struct Segmentation {
  // CV_32SC1: region index per pixel, -1 outside the mask. Every region is 8-connected.
  cv::Mat labels;
  std::vector<RegionStats> regions;
  RegionAdjacency adjacency;
  int pyramid_levels = 0;     // height of the hierarchy
  double milliseconds = 0.0;  // building the pyramid and labelling, not conversions or I/O
};

}  // namespace attend
