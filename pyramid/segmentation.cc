#include "pyramid/segmentation.h"

#include <algorithm>
#include <array>
#include <cstring>
#include <limits>
#include <opencv2/core/hal/hal.hpp>

#include "util/error.h"
#include "util/timer.h"
#include "util/vector_clones.h"

namespace attend {

const OptionFields<SegmentationOptions>& SegmentationOptions::Fields() {
  using O = SegmentationOptions;
  static const OptionFields<SegmentationOptions> fields = {
      {"t_max", &O::t_max, Range::Closed(0.001, 1000),
       "T_max of the threshold schedule, HSV cylinder units"},
      {"min_region_area", &O::min_region_area, Range::Closed(0, 1e6),
       "smaller regions merge into their closest neighbour, px; 0: keep the roots"},
      {"merge_spread", &O::merge_spread, Range::Closed(0, 100),
       "adjacent regions merge when their colours differ by at most this many times their "
       "spread; 0: off (the thesis)"}};
  return fields;
}

std::string SegmentationOptions::Check() const {
  const std::string error = CheckFieldRanges(*this, Fields());
  return error.empty() ? bip.Check() : error;
}

namespace {

// A pair of adjacent regions (a < b) and the number of 4-neighbour pixel edges between them.
struct RegionEdge {
  int a = 0;
  int b = 0;
  int length = 0;
};

// The saturation |(sx, sy)| of each pixel of a row of cylinder colours, for the whole row at
// once so that it vectorises: the squares in a loop compiled for AVX2 and for the baseline
// x86-64 (picked at run time), the square roots by cv::hal::sqrt32f (GCC does not vectorise
// std::sqrt under -fmath-errno). The same float operations as pixel by pixel (no FMA), so the
// same values.
ATTEND_VECTOR_CLONES void RowSaturation(const float* __restrict colour, int count,
                                        float* __restrict saturation) {
  for (int i = 0; i < count; ++i) {
    saturation[i] = colour[3 * i] * colour[3 * i] + colour[3 * i + 1] * colour[3 * i + 1];
  }
  cv::hal::sqrt32f(saturation, saturation, count);
}

// label = relabel[label] for the labelled pixels of a row. Every pixel reads relabel (at 0
// when unlabelled), so that the loop vectorises with gathers for AVX2.
ATTEND_VECTOR_CLONES void RelabelRow(const int* __restrict relabel, int count,
                                     int32_t* __restrict label) {
  for (int i = 0; i < count; ++i) {
    const int32_t l = label[i];
    const int32_t relabelled = relabel[l < 0 ? 0 : l];
    label[i] = l < 0 ? l : relabelled;
  }
}

}  // namespace

// Every buffer of the region statistics and of the merge, kept between frames so that a
// Segmenter allocates nothing for them after the first frame of a size.
struct Segmenter::Workspace {
  // With `spread`, also each region's sum of |c|^2 (into squares); without, squares are 0.
  void AccumulateRegions(const cv::Mat& labels, int num_regions, const cv::Mat& cylinder,
                         bool spread, std::vector<RegionStats>* regions);
  // The two merges work on one union-find state of the regions, with their sums: StartMerge
  // sets it up, MergeFlat and MergeSimilar join sets (each returns whether it joined any), and
  // ApplyMerge writes the result into the labels, statistics and edges.
  void StartMerge(const std::vector<RegionStats>& regions);
  bool MergeFlat(int min_area);
  bool MergeSimilar(float spread);
  int Find(int r);
  void Join(int absorbed, int into);
  int ApplyMerge(cv::Mat* labels, std::vector<RegionStats>* regions);
  void BuildAdjacency(int num_regions, RegionAdjacency* adjacency);
  void CombinePairs(int num_regions, const std::vector<RegionEdge>& pairs,
                    std::vector<RegionEdge>* combined);

  // The region adjacency as a flat edge list (a < b), combined.
  std::vector<RegionEdge> edges;
  std::vector<int> cursor;  // BuildAdjacency's
  // AccumulateRegions.
  std::vector<double> sums;
  std::vector<cv::Point> low;
  std::vector<cv::Point> high;
  std::vector<RegionEdge> runs;
  std::vector<float> row_saturation;
  // Per region: the sum over its pixels of |c|^2 (sx^2 + sy^2 + v^2), for its colour spread.
  std::vector<double> squares;
  // CombinePairs.
  std::vector<int> pair_offsets;
  std::vector<int> pair_cursor;
  std::vector<int> pair_slot;
  std::vector<RegionEdge> grouped;
  // MergeFlat.
  std::vector<int> offsets;
  std::vector<int> adjacent;
  std::vector<int> parent;
  std::vector<int> area;
  std::vector<int> next_member;
  std::vector<int> last_member;
  // sx, sy, v and saturation times area, and the sum of |c|^2.
  std::vector<std::array<double, 5>> merge_sums;
  std::vector<std::pair<int, int>> heap;  // (area, region)
  // MergeSimilar's edges in order: the bits of the float distance (non-negative, so they
  // order as the numbers do) above the edge's index.
  std::vector<uint64_t> order;
  std::vector<int> renumber;
  std::vector<int> relabel;
  std::vector<RegionStats> merged;
  std::vector<RegionEdge> pairs;
};

Segmenter::Segmenter(SegmentationOptions options, BipPool* pool)
    : options_(options),
      policy_(options.t_max),
      builder_(options.bip, pool),
      workspace_(std::make_unique<Workspace>()) {
  const std::string problem = options_.Check();
  ATTEND_CHECK(problem.empty()) << problem;
}

Segmenter::~Segmenter() = default;

void Segmenter::Segment(const cv::Mat& bgr, Segmentation* out) {
  BgrToCylinder(bgr, &cylinder_);
  SegmentCylinder(cylinder_, out);
}

// Adds up the lengths of repeated pairs without sorting: the pairs are grouped by their first
// region (counting sort), then each group's lengths are summed per second region.
void Segmenter::Workspace::CombinePairs(int num_regions, const std::vector<RegionEdge>& pairs,
                                        std::vector<RegionEdge>* combined) {
  std::vector<int>& offsets = pair_offsets;
  offsets.assign(num_regions + 1, 0);
  for (const RegionEdge& pair : pairs) ++offsets[pair.a + 1];
  for (int r = 0; r < num_regions; ++r) offsets[r + 1] += offsets[r];
  grouped.resize(pairs.size());
  std::vector<int>& cursor = pair_cursor;
  cursor.assign(offsets.begin(), offsets.end() - 1);
  for (const RegionEdge& pair : pairs) grouped[cursor[pair.a]++] = pair;
  combined->clear();
  std::vector<int>& slot = pair_slot;  // index in edges of (a, b) for the current a
  slot.assign(num_regions, -1);
  for (int a = 0; a < num_regions; ++a) {
    for (int k = offsets[a]; k < offsets[a + 1]; ++k) {
      const RegionEdge& pair = grouped[k];
      if (slot[pair.b] < 0 || (*combined)[slot[pair.b]].a != a) {
        slot[pair.b] = static_cast<int>(combined->size());
        combined->push_back({a, pair.b, 0});
      }
      (*combined)[slot[pair.b]].length += pair.length;
    }
  }
}

// One pass over the pixels: areas, sums, boxes, perimeters and the adjacent pairs (into
// edges).
void Segmenter::Workspace::AccumulateRegions(const cv::Mat& labels, int num_regions,
                                             const cv::Mat& cylinder, bool spread,
                                             std::vector<RegionStats>* regions) {
  ATTEND_CHECK(labels.type() == CV_32SC1 && cylinder.type() == CV_32FC3 &&
               labels.size() == cylinder.size())
      << "labels and cylinder image must match";
  regions->assign(num_regions, RegionStats{});
  // Sums in double: a 640x480 region of V = 255 reaches 8e7, beyond float's exact integers.
  sums.assign(4 * static_cast<size_t>(num_regions), 0.0);
  squares.assign(num_regions, 0.0);
  low.assign(num_regions, cv::Point(labels.cols, labels.rows));
  high.assign(num_regions, cv::Point(-1, -1));
  // Consecutive boundary pixels mostly separate the same pair of regions: store runs.
  runs.clear();
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
  row_saturation.resize(labels.cols);
  for (int row = 0; row < labels.rows; ++row) {
    const int32_t* label = labels.ptr<int32_t>(row);
    const int32_t* below = row + 1 < labels.rows ? labels.ptr<int32_t>(row + 1) : nullptr;
    const float* colour = cylinder.ptr<float>(row);
    float* saturation = row_saturation.data();
    RowSaturation(colour, labels.cols, saturation);
    // Runs of one label along the row: box and area once per run, sums per pixel.
    for (int col = 0; col < labels.cols;) {
      const int r = label[col];
      if (r < 0) {
        ++col;
        continue;
      }
      const int start = col;
      float s0 = 0.f, s1 = 0.f, s2 = 0.f, s3 = 0.f, s4 = 0.f;
      for (; col < labels.cols && label[col] == r; ++col) {
        const float* c = colour + 3 * col;
        s0 += c[0];
        s1 += c[1];
        s2 += c[2];
        s3 += saturation[col];
        if (spread) s4 += c[0] * c[0] + c[1] * c[1] + c[2] * c[2];
        if (below != nullptr && below[col] >= 0 && below[col] != r) boundary(r, below[col]);
      }
      RegionStats& region = (*regions)[r];
      region.area += col - start;
      double* sum = &sums[4 * static_cast<size_t>(r)];
      sum[0] += s0;
      sum[1] += s1;
      sum[2] += s2;
      sum[3] += s3;
      squares[r] += s4;
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
  CombinePairs(num_regions, runs, &edges);
}

// Refills the caller's adjacency in place (a Segmentation reused for a stream of frames keeps
// its storage): the boundaries in the order of `edges`, and each region's neighbours in that
// order too.
void Segmenter::Workspace::BuildAdjacency(int num_regions, RegionAdjacency* adjacency) {
  adjacency->boundaries.clear();
  adjacency->offsets.assign(static_cast<size_t>(num_regions) + 1, 0);
  for (const RegionEdge& edge : edges) {
    adjacency->boundaries.push_back({edge.a, edge.b, edge.length});
    ++adjacency->offsets[edge.a + 1];
    ++adjacency->offsets[edge.b + 1];
  }
  for (int r = 0; r < num_regions; ++r) adjacency->offsets[r + 1] += adjacency->offsets[r];
  adjacency->neighbours.resize(2 * edges.size());
  cursor.assign(adjacency->offsets.begin(), adjacency->offsets.end() - 1);
  for (const RegionEdge& edge : edges) {
    adjacency->neighbours[cursor[edge.a]++] = edge.b;
    adjacency->neighbours[cursor[edge.b]++] = edge.a;
  }
}

// The union-find state of both merges: every region its own set, with its sums.
void Segmenter::Workspace::StartMerge(const std::vector<RegionStats>& regions) {
  const int count = static_cast<int>(regions.size());
  parent.resize(count);
  area.resize(count);
  next_member.assign(count, -1);
  last_member.resize(count);
  merge_sums.resize(count);
  for (int r = 0; r < count; ++r) {
    const RegionStats& region = regions[r];
    parent[r] = r;
    last_member[r] = r;
    area[r] = region.area;
    const double a = region.area;
    merge_sums[r] = {region.colour.sx * a, region.colour.sy * a, region.colour.v * a,
                     region.saturation * a, squares[r]};
  }
}

int Segmenter::Workspace::Find(int r) {
  while (parent[r] != r) r = parent[r] = parent[parent[r]];
  return r;
}

// Joins the set of root `absorbed` into that of root `into`: sums add, member lists chain.
void Segmenter::Workspace::Join(int absorbed, int into) {
  parent[absorbed] = into;
  area[into] += area[absorbed];
  for (int c = 0; c < 5; ++c) merge_sums[into][c] += merge_sums[absorbed][c];
  next_member[last_member[into]] = absorbed;
  last_member[into] = last_member[absorbed];
}

// Merges every region smaller than `min_area` pixels into its adjacent region of closest mean
// colour, smallest first, until none is left that has a neighbour. Merged regions stay
// connected.
bool Segmenter::Workspace::MergeFlat(int min_area) {
  const int count = static_cast<int>(parent.size());
  // Adjacency of the original regions (CSR); a merged region's neighbours are those of its
  // members, which a linked list per region keeps.
  offsets.assign(count + 1, 0);
  adjacent.resize(2 * edges.size());
  for (const RegionEdge& edge : edges) {
    ++offsets[edge.a + 1];
    ++offsets[edge.b + 1];
  }
  for (int r = 0; r < count; ++r) offsets[r + 1] += offsets[r];
  {
    std::vector<int>& cursor = pair_cursor;
    cursor.assign(offsets.begin(), offsets.end() - 1);
    for (const RegionEdge& edge : edges) {
      adjacent[cursor[edge.a]++] = edge.b;
      adjacent[cursor[edge.b]++] = edge.a;
    }
  }
  const std::vector<std::array<double, 5>>& sum = merge_sums;
  // Smallest first (a min-heap); an entry whose area is stale was merged since it was queued.
  using Entry = std::pair<int, int>;  // (area, region)
  heap.clear();
  for (int r = 0; r < count; ++r) {
    if (area[r] < min_area) heap.push_back({area[r], r});
  }
  const std::greater<Entry> later;
  std::make_heap(heap.begin(), heap.end(), later);
  bool merged_any = false;
  while (!heap.empty()) {
    std::pop_heap(heap.begin(), heap.end(), later);
    const auto [queued_area, r] = heap.back();
    heap.pop_back();
    if (Find(r) != r || area[r] != queued_area) continue;
    int best = -1;
    double best_distance = std::numeric_limits<double>::infinity();
    for (int member = r; member >= 0; member = next_member[member]) {
      for (int k = offsets[member]; k < offsets[member + 1]; ++k) {
        const int m = Find(adjacent[k]);
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
    Join(r, best);
    if (area[best] < min_area) {
      heap.push_back({area[best], best});
      std::push_heap(heap.begin(), heap.end(), later);
    }
  }
  return merged_any;
}

// Merges adjacent regions whose mean colours are no further apart than `spread` times the
// root mean square of their two colour spreads (the standard deviations of their pixels'
// cylinder colours about their means): |m_a - m_b|^2 <= spread^2 (s_a^2 + s_b^2) / 2. The
// adjacent pairs are taken in order of increasing distance between their means at the start,
// each tested with the statistics of the regions as merged so far (docs/PYRAMID.md,
// "Merging by spread"). A textured region, whose pixels spread widely, absorbs neighbours of
// a similar mean; flat regions of different colours stay apart. It starts from the sets as
// MergeFlat left them: an edge of the regions before the merges is one of the sets it joins.
bool Segmenter::Workspace::MergeSimilar(float spread) {
  const std::vector<std::array<double, 5>>& sum = merge_sums;
  auto squared_distance = [&sum, this](int a, int b) {
    double distance = 0.0;
    for (int c = 0; c < 3; ++c) {
      const double d = sum[a][c] / area[a] - sum[b][c] / area[b];
      distance += d * d;
    }
    return distance;
  };
  // The mean of |c - m|^2 over a region's pixels; rounding may leave a tiny negative value.
  auto variance = [&sum, this](int r) {
    double mean_square = 0.0;
    for (int c = 0; c < 3; ++c) {
      const double m = sum[r][c] / area[r];
      mean_square += m * m;
    }
    return std::max(0.0, sum[r][4] / area[r] - mean_square);
  };
  order.clear();
  for (size_t e = 0; e < edges.size(); ++e) {
    const int a = Find(edges[e].a);
    const int b = Find(edges[e].b);
    if (a == b) continue;
    const float distance = static_cast<float>(squared_distance(a, b));
    uint32_t bits = 0;
    std::memcpy(&bits, &distance, sizeof(bits));
    order.push_back(static_cast<uint64_t>(bits) << 32 | static_cast<uint32_t>(e));
  }
  std::sort(order.begin(), order.end());
  const double factor = 0.5 * static_cast<double>(spread) * spread;
  bool merged_any = false;
  for (const uint64_t key : order) {
    const uint32_t e = static_cast<uint32_t>(key);
    int a = Find(edges[e].a);
    int b = Find(edges[e].b);
    if (a == b) continue;
    if (squared_distance(a, b) > factor * (variance(a) + variance(b))) continue;
    if (area[a] < area[b]) std::swap(a, b);
    Join(b, a);
    merged_any = true;
  }
  return merged_any;
}

// Relabels `labels` after a merge (regions numbered by first appearance) and updates
// `regions` and the edges exactly, without another pass over the pixels.
// Returns the new number of regions.
int Segmenter::Workspace::ApplyMerge(cv::Mat* labels, std::vector<RegionStats>* regions) {
  const int count = static_cast<int>(regions->size());
  const std::vector<std::array<double, 5>>& sum = merge_sums;
  // Number the surviving regions by first appearance. The regions are numbered so already, so
  // a merged region first appears where its lowest-numbered member does: numbering the roots
  // in order of their lowest member gives the numbers a scan of the pixels would.
  renumber.assign(count, -1);  // per root
  relabel.resize(count);       // per original region
  int next = 0;
  for (int r = 0; r < count; ++r) {
    const int root = Find(r);
    if (renumber[root] < 0) renumber[root] = next++;
    relabel[r] = renumber[root];
  }
  for (int row = 0; row < labels->rows; ++row) {
    RelabelRow(relabel.data(), labels->cols, labels->ptr<int32_t>(row));
  }
  // Statistics of the merged regions: sums add, boxes join, and a perimeter is the length of
  // the boundaries that remain between different regions.
  merged.assign(next, RegionStats{});
  for (int r = 0; r < count; ++r) {
    const RegionStats& source = (*regions)[r];
    RegionStats& region = merged[relabel[r]];
    region.bbox = region.area == 0 ? source.bbox : (region.bbox | source.bbox);
    region.area += source.area;
  }
  for (int r = 0; r < count; ++r) {
    if (Find(r) != r) continue;
    RegionStats& region = merged[renumber[r]];
    region.colour = {static_cast<float>(sum[r][0] / area[r]),
                     static_cast<float>(sum[r][1] / area[r]),
                     static_cast<float>(sum[r][2] / area[r])};
    region.intensity = region.colour.v;
    region.saturation = static_cast<float>(sum[r][3] / area[r]);
  }
  pairs.clear();
  for (const RegionEdge& edge : edges) {
    const int a = relabel[edge.a], b = relabel[edge.b];
    if (a != b) pairs.push_back({std::min(a, b), std::max(a, b), edge.length});
  }
  CombinePairs(next, pairs, &edges);
  for (const RegionEdge& edge : edges) {
    merged[edge.a].perimeter += edge.length;
    merged[edge.b].perimeter += edge.length;
  }
  regions->swap(merged);
  return next;
}

void Segmenter::SegmentCylinder(const cv::Mat& cylinder, Segmentation* out, const cv::Mat& mask) {
  const Stopwatch watch;
  const Bip& bip = builder_.Build(cylinder, policy_, mask);
  int regions = bip.LabelRoots(&out->labels);
  out->pyramid_levels = bip.num_levels();
  workspace_->AccumulateRegions(out->labels, regions, cylinder, options_.merge_spread > 0.f,
                                &out->regions);
  if (options_.min_region_area > 1 || options_.merge_spread > 0.f) {
    Workspace& merge = *workspace_;
    merge.StartMerge(out->regions);
    bool merged = options_.min_region_area > 1 && merge.MergeFlat(options_.min_region_area);
    if (options_.merge_spread > 0.f) merged = merge.MergeSimilar(options_.merge_spread) || merged;
    if (merged) regions = merge.ApplyMerge(&out->labels, &out->regions);
  }
  workspace_->BuildAdjacency(regions, &out->adjacency);
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
