#include "semiattentive/candidates.h"

#include <cmath>
#include <tuple>

#include <algorithm>

#include "pyramid/similarity.h"

namespace attend {

namespace {

// Per saliency region of `c->labels`: the sum of `inhibited`, the area, the peak and the bounds.
void Measure(const cv::Mat& inhibited, int count, Candidates* c) {
  c->sum.assign(count, 0.0);
  c->area.assign(count, 0);
  c->peak.assign(count, cv::Point());
  c->peak_value.assign(count, -1.f);
  c->low.assign(count, {c->labels.cols, c->labels.rows});
  c->high.assign(count, {-1, -1});
  // A row at a time, a run of one label at a time: the sums, peaks and extents are taken
  // in the same order as pixel by pixel, so they are the same, at a fraction of the cost.
  for (int y = 0; y < c->labels.rows; ++y) {
    const int* label = c->labels.ptr<int>(y);
    const float* s = inhibited.ptr<float>(y);
    for (int x = 0; x < c->labels.cols;) {
      const int r = label[x];
      const int first = x;
      while (x < c->labels.cols && label[x] == r) ++x;
      if (r < 0) continue;
      double& sum = c->sum[r];
      float& peak = c->peak_value[r];
      for (int i = first; i < x; ++i) {
        sum += s[i];
        if (s[i] > peak) peak = s[i], c->peak[r] = {i, y};
      }
      c->area[r] += x - first;
      c->low[r] = {std::min(c->low[r].x, first), std::min(c->low[r].y, y)};
      c->high[r] = {std::max(c->high[r].x, x - 1), std::max(c->high[r].y, y)};
    }
  }
}

}  // namespace

CandidateFinder::CandidateFinder(const SelectOptions& options, BipPool* pool)
    : min_saliency_(options.min_saliency),
      min_area_(options.min_area),
      t_max_(options.saliency_t_max),
      builder_(BipOptions{}, pool) {}

Candidates CandidateFinder::Find(const cv::Mat& inhibited) {
  Candidates c;
  // The buffers are kept from frame to frame: fresh ones of 1-4 MB a frame (640x480) each
  // came from the kernel as new, zeroed pages, which cost the stage more than its arithmetic
  // (docs/PERFORMANCE.md, "Where 640x480 goes").
  // The pyramid's features: the saliency times 255 and two zero components, made a row at a
  // time (no whole scaled map and zero plane beside them: 2.4 MB at 640x480).
  features_.create(inhibited.size(), CV_32FC3);
  for (int y = 0; y < inhibited.rows; ++y) {
    inhibited.row(y).convertTo(scaled_row_, CV_32F, 255.0);
    const float* in = scaled_row_.ptr<float>();
    float* out = features_.ptr<float>(y);
    for (int x = 0; x < inhibited.cols; ++x) {
      out[3 * x] = in[x];
      out[3 * x + 1] = 0.f;
      out[3 * x + 2] = 0.f;
    }
  }
  const Bip& bip = builder_.Build(features_, HsvSimilarity(t_max_));
  const int count = bip.LabelRoots(&c.labels);
  builder_.Release();  // its levels serve the other pyramids of the frame
  Measure(inhibited, count, &c);
  for (int r = 0; r < count; ++r) {
    const double mean = c.area[r] > 0 ? c.sum[r] / c.area[r] : 0.0;
    if (mean >= min_saliency_ && c.area[r] >= min_area_) c.ranked.push_back({mean * c.area[r], r});
  }
  std::stable_sort(c.ranked.begin(), c.ranked.end(),
                   [](const auto& a, const auto& b) { return a.first > b.first; });
  return c;
}

void RankCandidates(const SelectOptions& options, const cv::Point2d* focus,
                    const std::vector<Detection>& detections, cv::Size image,
                    Candidates* candidates) {
  Candidates& c = *candidates;
  const double diagonal = std::hypot(image.width, image.height);
  const double s = options.proximity * diagonal;
  std::vector<std::tuple<int, double, int>> ranked;  // (face, score, region)
  for (const auto& [mass, r] : c.ranked) {
    double score = mass;
    if (options.order == CandidateOrder::kPeak) score = c.peak_value[r];
    if (options.order == CandidateOrder::kMean) score = c.sum[r] / c.area[r];
    if (focus != nullptr && s > 0.0) {
      const double dx = c.peak[r].x - focus->x, dy = c.peak[r].y - focus->y;
      score *= std::exp(-(dx * dx + dy * dy) / (2.0 * s * s));
    }
    int face = 0;
    if (options.faces_first) {
      for (const Detection& d : detections) {
        if (d.label == "face" && d.box.contains(c.peak[r])) face = 1;
      }
    }
    ranked.emplace_back(face, score, r);
  }
  std::stable_sort(ranked.begin(), ranked.end(), [](const auto& a, const auto& b) {
    if (std::get<0>(a) != std::get<0>(b)) return std::get<0>(a) > std::get<0>(b);
    return std::get<1>(a) > std::get<1>(b);
  });
  for (size_t k = 0; k < ranked.size(); ++k) {
    c.ranked[k] = {std::get<1>(ranked[k]), std::get<2>(ranked[k])};
  }
}

CandidateRegions RegionsUnder(const Candidates& c, const Segmentation& segmentation,
                              const cv::Mat& covered) {
  CandidateRegions under;
  std::vector<int> candidate_of(c.sum.size(), -1);
  for (size_t k = 0; k < c.ranked.size(); ++k) {
    candidate_of[c.ranked[k].second] = static_cast<int>(k);
  }
  under.overlaps.resize(c.ranked.size());
  under.taken.assign(segmentation.regions.size(), 0);
  const cv::Mat& colour = segmentation.labels;
  for (int y = 0; y < c.labels.rows; ++y) {
    const int* label = c.labels.ptr<int>(y);
    const int* region = colour.ptr<int>(y);
    const uchar* cover = covered.ptr<uchar>(y);
    for (int x = 0; x < c.labels.cols; ++x) {
      if (region[x] < 0) continue;
      if (cover[x]) under.taken[region[x]] = 1;
      if (label[x] >= 0 && candidate_of[label[x]] >= 0) {
        ++under.overlaps[candidate_of[label[x]]][region[x]];
      }
    }
  }
  return under;
}

}  // namespace attend
