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

void Segmenter::SegmentCylinder(const cv::Mat& cylinder, Segmentation* out, const cv::Mat& mask) {
  const Stopwatch watch;
  const Bip& bip = builder_.Build(cylinder, policy_, mask);
  const int regions = bip.LabelRoots(&out->labels);
  out->pyramid_levels = bip.num_levels();
  ComputeRegionStats(out->labels, regions, cylinder, &out->regions, &out->graph, &boundary_runs_);
  if (options_.min_region_area > 1) {
    MergeSmallRegions(options_.min_region_area, &out->labels, &out->regions, &out->graph);
  }
  out->milliseconds = watch.ElapsedMs();
}

int MergeSmallRegions(int min_area, cv::Mat* labels, std::vector<RegionStats>* regions,
                      RegionGraph* graph) {
  const int count = static_cast<int>(regions->size());
  std::vector<int> parent(count), area(count);
  std::vector<std::array<double, 4>> sum(count);  // sx, sy, v, saturation times area
  std::vector<std::vector<int>> neighbours(count);
  std::vector<size_t> compact_size(count, 0);
  for (int r = 0; r < count; ++r) {
    const RegionStats& region = (*regions)[r];
    parent[r] = r;
    area[r] = region.area;
    const double a = region.area;
    sum[r] = {region.colour.sx * a, region.colour.sy * a, region.colour.v * a,
              region.saturation * a};
  }
  for (auto [e, end] = boost::edges(*graph); e != end; ++e) {
    const int a = static_cast<int>(boost::source(*e, *graph));
    const int b = static_cast<int>(boost::target(*e, *graph));
    neighbours[a].push_back(b);
    neighbours[b].push_back(a);
  }
  auto find = [&](int r) {
    while (parent[r] != r) r = parent[r] = parent[parent[r]];
    return r;
  };
  // Smallest first; an entry whose area is stale was merged since it was queued.
  using Entry = std::pair<int, int>;  // (area, region)
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
  for (int r = 0; r < count; ++r) {
    if (area[r] < min_area) queue.push({area[r], r});
  }
  bool merged_any = false;
  while (!queue.empty()) {
    const auto [queued_area, r] = queue.top();
    queue.pop();
    if (find(r) != r || area[r] != queued_area) continue;
    int best = -1;
    double best_distance = std::numeric_limits<double>::infinity();
    for (int n : neighbours[r]) {
      const int m = find(n);
      if (m == r) continue;
      double distance = 0.0;
      for (int k = 0; k < 3; ++k) {
        const double d = sum[r][k] / area[r] - sum[m][k] / area[m];
        distance += d * d;
      }
      if (distance < best_distance) {
        best_distance = distance;
        best = m;
      }
    }
    if (best < 0) continue;  // an isolated region (inside a mask) stays
    merged_any = true;
    parent[r] = best;
    area[best] += area[r];
    for (int k = 0; k < 4; ++k) sum[best][k] += sum[r][k];
    std::vector<int>& joined = neighbours[best];
    joined.insert(joined.end(), neighbours[r].begin(), neighbours[r].end());
    neighbours[r].clear();
    neighbours[r].shrink_to_fit();
    // A region that swallows many small ones would collect their lists again and again:
    // compact it to its distinct current neighbours whenever it has doubled.
    if (joined.size() > 32 && joined.size() > 2 * compact_size[best]) {
      for (int& n : joined) n = find(n);
      std::sort(joined.begin(), joined.end());
      joined.erase(std::unique(joined.begin(), joined.end()), joined.end());
      joined.erase(std::remove(joined.begin(), joined.end(), best), joined.end());
      compact_size[best] = joined.size();
    }
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
    const int target = renumber[find(r)];
    const RegionStats& source = (*regions)[r];
    RegionStats& region = merged[target];
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
  std::vector<std::pair<uint64_t, int>> pairs;
  for (auto [e, end] = boost::edges(*graph); e != end; ++e) {
    const int a = renumber[find(static_cast<int>(boost::source(*e, *graph)))];
    const int b = renumber[find(static_cast<int>(boost::target(*e, *graph)))];
    if (a == b) continue;
    const uint64_t key = (static_cast<uint64_t>(std::min(a, b)) << 32) | std::max(a, b);
    pairs.emplace_back(key, (*graph)[*e].length);
  }
  std::sort(pairs.begin(), pairs.end());
  std::vector<std::pair<int, int>> edge_ends;
  std::vector<RegionBoundary> lengths;
  for (size_t i = 0; i < pairs.size();) {
    size_t j = i;
    int length = 0;
    while (j < pairs.size() && pairs[j].first == pairs[i].first) length += pairs[j++].second;
    const int a = static_cast<int>(pairs[i].first >> 32);
    const int b = static_cast<int>(pairs[i].first & 0xffffffffu);
    edge_ends.emplace_back(a, b);
    lengths.push_back({length});
    merged[a].perimeter += length;
    merged[b].perimeter += length;
    i = j;
  }
  *graph = RegionGraph(edge_ends.begin(), edge_ends.end(), lengths.begin(), next);
  *regions = std::move(merged);
  return next;
}

void ComputeRegionStats(const cv::Mat& labels, int num_regions, const cv::Mat& cylinder,
                        std::vector<RegionStats>* regions, RegionGraph* graph,
                        std::vector<uint64_t>* scratch) {
  ATTEND_CHECK(labels.type() == CV_32SC1 && cylinder.type() == CV_32FC3 &&
               labels.size() == cylinder.size())
      << "labels and cylinder image must match";
  regions->assign(num_regions, RegionStats{});
  // Sums in double: a 640x480 region of V = 255 reaches 8e7, beyond float's exact integers.
  std::vector<double> sums(4 * static_cast<size_t>(num_regions), 0.0);
  std::vector<cv::Point> low(num_regions, cv::Point(labels.cols, labels.rows));
  std::vector<cv::Point> high(num_regions, cv::Point(-1, -1));
  scratch->clear();
  // Consecutive boundary pixels mostly separate the same pair of regions: count runs.
  uint64_t run_key = 0;
  uint32_t run_length = 0;
  auto boundary = [&](int a, int b) {
    ++(*regions)[a].perimeter;
    ++(*regions)[b].perimeter;
    const uint64_t key = (static_cast<uint64_t>(std::min(a, b)) << 32) | std::max(a, b);
    if (run_length > 0 && key == run_key) {
      ++run_length;
      return;
    }
    if (run_length > 0) {
      scratch->push_back(run_key);
      scratch->push_back(run_length);
    }
    run_key = key;
    run_length = 1;
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
  if (run_length > 0) {
    scratch->push_back(run_key);
    scratch->push_back(run_length);
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
  // Merge the runs by pair into graph edges without sorting: group the runs by their smaller
  // region (counting sort), then add up each group's lengths per neighbour with a slot index.
  const size_t runs = scratch->size() / 2;
  std::vector<int> offsets(num_regions + 1, 0);
  for (size_t i = 0; i < runs; ++i) ++offsets[((*scratch)[2 * i] >> 32) + 1];
  for (int r = 0; r < num_regions; ++r) offsets[r + 1] += offsets[r];
  std::vector<std::pair<int, int>> grouped(runs);  // (other region, length)
  std::vector<int> cursor(offsets.begin(), offsets.end() - 1);
  for (size_t i = 0; i < runs; ++i) {
    const uint64_t key = (*scratch)[2 * i];
    grouped[cursor[key >> 32]++] = {static_cast<int>(key & 0xffffffffu),
                                    static_cast<int>((*scratch)[2 * i + 1])};
  }
  using EdgePair = std::pair<int, int>;
  std::vector<EdgePair> edge_ends;
  std::vector<RegionBoundary> lengths;
  std::vector<int> slot(num_regions, -1);  // index in edge_ends of (a, b) for the current a
  for (int a = 0; a < num_regions; ++a) {
    for (int k = offsets[a]; k < offsets[a + 1]; ++k) {
      const auto [b, length] = grouped[k];
      if (slot[b] < 0 || edge_ends[slot[b]].first != a) {
        slot[b] = static_cast<int>(edge_ends.size());
        edge_ends.emplace_back(a, b);
        lengths.push_back({0});
      }
      lengths[slot[b]].length += length;
    }
  }
  *graph = RegionGraph(edge_ends.begin(), edge_ends.end(), lengths.begin(), num_regions);
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
