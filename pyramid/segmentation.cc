#include "pyramid/segmentation.h"

#include <algorithm>
#include <array>
#include <limits>
#include <queue>

#include "util/error.h"
#include "util/timer.h"

namespace attend {

std::string SegmentationOptions::Check() const {
  if (!(t_max > 0.f) || t_max > 1000.f) return "t_max must be in (0, 1000]";
  if (min_region_area < 0) return "min_region_area must be >= 0";
  return bip.Check();
}

Segmenter::Segmenter(SegmentationOptions options)
    : options_(options), policy_(options.t_max), builder_(options.bip) {
  const std::string problem = options_.Check();
  ATTEND_CHECK(problem.empty()) << problem;
}

void Segmenter::Segment(const cv::Mat& bgr, Segmentation* out) {
  BgrToCylinder(bgr, &cylinder_);
  SegmentCylinder(cylinder_, out);
}

namespace {

// A pair of adjacent regions (a < b) and the number of 4-neighbour pixel edges between them.
struct RegionEdge {
  int a = 0;
  int b = 0;
  int length = 0;
};

// Adds up the lengths of repeated pairs without sorting: the pairs are grouped by their first
// region (counting sort), then each group's lengths are summed per second region.
void CombinePairs(int num_regions, const std::vector<RegionEdge>& pairs,
                  std::vector<RegionEdge>* edges) {
  std::vector<int> offsets(num_regions + 1, 0);
  for (const RegionEdge& pair : pairs) ++offsets[pair.a + 1];
  for (int r = 0; r < num_regions; ++r) offsets[r + 1] += offsets[r];
  std::vector<RegionEdge> grouped(pairs.size());
  std::vector<int> cursor(offsets.begin(), offsets.end() - 1);
  for (const RegionEdge& pair : pairs) grouped[cursor[pair.a]++] = pair;
  edges->clear();
  std::vector<int> slot(num_regions, -1);  // index in edges of (a, b) for the current a
  for (int a = 0; a < num_regions; ++a) {
    for (int k = offsets[a]; k < offsets[a + 1]; ++k) {
      const RegionEdge& pair = grouped[k];
      if (slot[pair.b] < 0 || (*edges)[slot[pair.b]].a != a) {
        slot[pair.b] = static_cast<int>(edges->size());
        edges->push_back({a, pair.b, 0});
      }
      (*edges)[slot[pair.b]].length += pair.length;
    }
  }
}

// One pass over the pixels: areas, sums, boxes, perimeters and the adjacent pairs.
void AccumulateRegions(const cv::Mat& labels, int num_regions, const cv::Mat& cylinder,
                       std::vector<RegionStats>* regions, std::vector<RegionEdge>* edges) {
  ATTEND_CHECK(labels.type() == CV_32SC1 && cylinder.type() == CV_32FC3 &&
               labels.size() == cylinder.size())
      << "labels and cylinder image must match";
  regions->assign(num_regions, RegionStats{});
  // Sums in double: a 640x480 region of V = 255 reaches 8e7, beyond float's exact integers.
  std::vector<double> sums(4 * static_cast<size_t>(num_regions), 0.0);
  std::vector<cv::Point> low(num_regions, cv::Point(labels.cols, labels.rows));
  std::vector<cv::Point> high(num_regions, cv::Point(-1, -1));
  // Consecutive boundary pixels mostly separate the same pair of regions: store runs.
  std::vector<RegionEdge> runs;
  auto boundary = [&](int a, int b) {
    ++(*regions)[a].perimeter;
    ++(*regions)[b].perimeter;
    if (a > b) std::swap(a, b);
    if (!runs.empty() && runs.back().a == a && runs.back().b == b) {
      ++runs.back().length;
    } else {
      runs.push_back({a, b, 1});
    }
  };
  for (int row = 0; row < labels.rows; ++row) {
    const int32_t* label = labels.ptr<int32_t>(row);
    const int32_t* below = row + 1 < labels.rows ? labels.ptr<int32_t>(row + 1) : nullptr;
    const float* colour = cylinder.ptr<float>(row);
    // Runs of one label along the row: box and area once per run, sums per pixel.
    for (int col = 0; col < labels.cols;) {
      const int r = label[col];
      if (r < 0) {
        ++col;
        continue;
      }
      const int start = col;
      float s0 = 0.f, s1 = 0.f, s2 = 0.f, s3 = 0.f;
      for (; col < labels.cols && label[col] == r; ++col) {
        const float* c = colour + 3 * col;
        s0 += c[0];
        s1 += c[1];
        s2 += c[2];
        s3 += std::sqrt(c[0] * c[0] + c[1] * c[1]);
        if (below != nullptr && below[col] >= 0 && below[col] != r) boundary(r, below[col]);
      }
      RegionStats& region = (*regions)[r];
      region.area += col - start;
      double* sum = &sums[4 * static_cast<size_t>(r)];
      sum[0] += s0;
      sum[1] += s1;
      sum[2] += s2;
      sum[3] += s3;
      low[r].x = std::min(low[r].x, start);
      low[r].y = std::min(low[r].y, row);
      high[r].x = std::max(high[r].x, col - 1);
      high[r].y = std::max(high[r].y, row);
      if (col < labels.cols && label[col] >= 0) boundary(r, label[col]);
    }
  }
  for (int r = 0; r < num_regions; ++r) {
    RegionStats& region = (*regions)[r];
    ATTEND_CHECK(region.area > 0) << "region " << r << " has no pixel";
    const double* sum = &sums[4 * static_cast<size_t>(r)];
    region.colour = {static_cast<float>(sum[0] / region.area),
                     static_cast<float>(sum[1] / region.area),
                     static_cast<float>(sum[2] / region.area)};
    region.intensity = region.colour.v;
    region.saturation = static_cast<float>(sum[3] / region.area);
    region.bbox = cv::Rect(low[r], high[r] + cv::Point(1, 1));
  }
  CombinePairs(num_regions, runs, edges);
}

void BuildGraph(int num_regions, const std::vector<RegionEdge>& edges, RegionGraph* graph) {
  std::vector<std::pair<int, int>> ends;
  std::vector<RegionBoundary> lengths;
  ends.reserve(edges.size());
  lengths.reserve(edges.size());
  for (const RegionEdge& edge : edges) {
    ends.emplace_back(edge.a, edge.b);
    lengths.push_back({edge.length});
  }
  *graph = RegionGraph(ends.begin(), ends.end(), lengths.begin(), num_regions);
}

// Merges every region smaller than `min_area` pixels into its adjacent region of closest mean
// colour, smallest first, until none is left that has a neighbour. Relabels `labels` (regions
// numbered by first appearance) and updates `regions` and `edges` exactly, without another
// pass over the pixels. Merged regions stay connected. Returns the new number of regions.
int MergeFlat(int min_area, cv::Mat* labels, std::vector<RegionStats>* regions,
              std::vector<RegionEdge>* edges) {
  const int count = static_cast<int>(regions->size());
  // Adjacency of the original regions (CSR); a merged region's neighbours are those of its
  // members, which a linked list per region keeps.
  std::vector<int> offsets(count + 1, 0), adjacent(2 * edges->size());
  for (const RegionEdge& edge : *edges) {
    ++offsets[edge.a + 1];
    ++offsets[edge.b + 1];
  }
  for (int r = 0; r < count; ++r) offsets[r + 1] += offsets[r];
  {
    std::vector<int> cursor(offsets.begin(), offsets.end() - 1);
    for (const RegionEdge& edge : *edges) {
      adjacent[cursor[edge.a]++] = edge.b;
      adjacent[cursor[edge.b]++] = edge.a;
    }
  }
  std::vector<int> parent(count), area(count), next_member(count, -1), last_member(count);
  std::vector<std::array<double, 4>> sum(count);  // sx, sy, v, saturation times area
  for (int r = 0; r < count; ++r) {
    const RegionStats& region = (*regions)[r];
    parent[r] = r;
    last_member[r] = r;
    area[r] = region.area;
    const double a = region.area;
    sum[r] = {region.colour.sx * a, region.colour.sy * a, region.colour.v * a,
              region.saturation * a};
  }
  auto find = [&](int r) {
    while (parent[r] != r) r = parent[r] = parent[parent[r]];
    return r;
  };
  // Smallest first; an entry whose area is stale was merged since it was queued.
  using Entry = std::pair<int, int>;  // (area, region)
  std::vector<Entry> heap;
  for (int r = 0; r < count; ++r) {
    if (area[r] < min_area) heap.push_back({area[r], r});
  }
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue(std::greater<Entry>(),
                                                                            std::move(heap));
  bool merged_any = false;
  while (!queue.empty()) {
    const auto [queued_area, r] = queue.top();
    queue.pop();
    if (find(r) != r || area[r] != queued_area) continue;
    int best = -1;
    double best_distance = std::numeric_limits<double>::infinity();
    for (int member = r; member >= 0; member = next_member[member]) {
      for (int k = offsets[member]; k < offsets[member + 1]; ++k) {
        const int m = find(adjacent[k]);
        if (m == r) continue;
        double distance = 0.0;
        for (int c = 0; c < 3; ++c) {
          const double d = sum[r][c] / area[r] - sum[m][c] / area[m];
          distance += d * d;
        }
        if (distance < best_distance) {
          best_distance = distance;
          best = m;
        }
      }
    }
    if (best < 0) continue;  // an isolated region (inside a mask) stays
    merged_any = true;
    parent[r] = best;
    area[best] += area[r];
    for (int c = 0; c < 4; ++c) sum[best][c] += sum[r][c];
    next_member[last_member[best]] = r;
    last_member[best] = last_member[r];
    if (area[best] < min_area) queue.push({area[best], best});
  }
  if (!merged_any) return count;

  // Relabel, numbering the surviving regions by first appearance.
  std::vector<int> renumber(count, -1);
  int next = 0;
  for (int row = 0; row < labels->rows; ++row) {
    int32_t* label = labels->ptr<int32_t>(row);
    for (int col = 0; col < labels->cols; ++col) {
      if (label[col] < 0) continue;
      const int root = find(label[col]);
      if (renumber[root] < 0) renumber[root] = next++;
      label[col] = renumber[root];
    }
  }
  // Statistics of the merged regions: sums add, boxes join, and a perimeter is the length of
  // the boundaries that remain between different regions.
  std::vector<RegionStats> merged(next);
  for (int r = 0; r < count; ++r) {
    const RegionStats& source = (*regions)[r];
    RegionStats& region = merged[renumber[find(r)]];
    region.bbox = region.area == 0 ? source.bbox : (region.bbox | source.bbox);
    region.area += source.area;
  }
  for (int r = 0; r < count; ++r) {
    if (find(r) != r) continue;
    RegionStats& region = merged[renumber[r]];
    region.colour = {static_cast<float>(sum[r][0] / area[r]),
                     static_cast<float>(sum[r][1] / area[r]),
                     static_cast<float>(sum[r][2] / area[r])};
    region.intensity = region.colour.v;
    region.saturation = static_cast<float>(sum[r][3] / area[r]);
  }
  std::vector<RegionEdge> pairs;
  pairs.reserve(edges->size());
  for (const RegionEdge& edge : *edges) {
    const int a = renumber[find(edge.a)], b = renumber[find(edge.b)];
    if (a != b) pairs.push_back({std::min(a, b), std::max(a, b), edge.length});
  }
  CombinePairs(next, pairs, edges);
  for (const RegionEdge& edge : *edges) {
    merged[edge.a].perimeter += edge.length;
    merged[edge.b].perimeter += edge.length;
  }
  *regions = std::move(merged);
  return next;
}

}  // namespace

void Segmenter::SegmentCylinder(const cv::Mat& cylinder, Segmentation* out, const cv::Mat& mask) {
  const Stopwatch watch;
  const Bip& bip = builder_.Build(cylinder, policy_, mask);
  int regions = bip.LabelRoots(&out->labels);
  out->pyramid_levels = bip.num_levels();
  std::vector<RegionEdge> edges;
  AccumulateRegions(out->labels, regions, cylinder, &out->regions, &edges);
  if (options_.min_region_area > 1) {
    regions = MergeFlat(options_.min_region_area, &out->labels, &out->regions, &edges);
  }
  BuildGraph(regions, edges, &out->graph);
  out->milliseconds = watch.ElapsedMs();
}

cv::Mat FalseColour(const cv::Mat& labels) {
  cv::Mat image(labels.size(), CV_8UC3);
  for (int row = 0; row < labels.rows; ++row) {
    const int32_t* label = labels.ptr<int32_t>(row);
    cv::Vec3b* out = image.ptr<cv::Vec3b>(row);
    for (int col = 0; col < labels.cols; ++col) {
      if (label[col] < 0) {
        out[col] = cv::Vec3b(0, 0, 0);
        continue;
      }
      // A multiplicative hash spreads consecutive labels over the colour cube.
      const uint32_t h = static_cast<uint32_t>(label[col] + 1) * 2654435761u;
      out[col] = cv::Vec3b(64 + (h & 0xbf), 64 + ((h >> 8) & 0xbf), 64 + ((h >> 16) & 0xbf));
    }
  }
  return image;
}

cv::Mat MeanColourImage(const cv::Mat& labels, const std::vector<RegionStats>& regions) {
  std::vector<cv::Vec3b> palette(regions.size());
  for (size_t r = 0; r < regions.size(); ++r) {
    const cv::Vec3f rgb = RgbFromCylinder(regions[r].colour);
    palette[r] = cv::Vec3b(cv::saturate_cast<uchar>(rgb[2]), cv::saturate_cast<uchar>(rgb[1]),
                           cv::saturate_cast<uchar>(rgb[0]));
  }
  cv::Mat image(labels.size(), CV_8UC3);
  for (int row = 0; row < labels.rows; ++row) {
    const int32_t* label = labels.ptr<int32_t>(row);
    cv::Vec3b* out = image.ptr<cv::Vec3b>(row);
    for (int col = 0; col < labels.cols; ++col) {
      out[col] = label[col] < 0 ? cv::Vec3b(0, 0, 0) : palette[label[col]];
    }
  }
  return image;
}

}  // namespace attend
