#include "pyramid/metrics.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "util/error.h"

namespace attend {

namespace {

// Per-region sums of one pass over the pixels. The colour sums are taken relative to the
// region's first pixel (raster order): a shifted sum keeps e^2 = sum |c - c0|^2 - |sum (c - c0)|^2
// / A free of the cancellation of the textbook formula, and exactly zero for a flat region.
struct RegionSums {
  int64_t area = 0;
  int reference[3] = {0, 0, 0};  // BGR of the first pixel
  int64_t sum[3] = {0, 0, 0};    // sum of (c - reference), per channel
  int64_t sum_squares = 0;       // sum of |c - reference|^2
};

void CheckImageAndLabels(const cv::Mat& bgr, const cv::Mat& labels, const char* caller) {
  ATTEND_CHECK(bgr.type() == CV_8UC3) << caller << ": image type " << bgr.type();
  ATTEND_CHECK(labels.type() == CV_32SC1) << caller << ": label type " << labels.type();
  ATTEND_CHECK(labels.size() == bgr.size())
      << caller << ": labels " << labels.cols << "x" << labels.rows << ", image " << bgr.cols << "x"
      << bgr.rows;
}

// Sums per label over the pixels with label >= 0, indexed by label (labels that never occur
// keep area 0).
std::vector<RegionSums> SumRegions(const cv::Mat& bgr, const cv::Mat& labels) {
  std::vector<RegionSums> sums;
  for (int row = 0; row < labels.rows; ++row) {
    const int32_t* label = labels.ptr<int32_t>(row);
    const cv::Vec3b* colour = bgr.ptr<cv::Vec3b>(row);
    for (int col = 0; col < labels.cols; ++col) {
      const int32_t l = label[col];
      if (l < 0) continue;
      if (static_cast<size_t>(l) >= sums.size()) sums.resize(static_cast<size_t>(l) + 1);
      RegionSums& s = sums[l];
      if (s.area == 0) {
        for (int c = 0; c < 3; ++c) s.reference[c] = colour[col][c];
      }
      ++s.area;
      for (int c = 0; c < 3; ++c) {
        const int d = colour[col][c] - s.reference[c];
        s.sum[c] += d;
        s.sum_squares += d * d;
      }
    }
  }
  return sums;
}

// e^2: the sum over the region's pixels of the squared Euclidean distance to its mean colour.
double SquaredColourError(const RegionSums& s) {
  double sum_norm = 0.0;
  for (int c = 0; c < 3; ++c) sum_norm += static_cast<double>(s.sum[c]) * s.sum[c];
  // Rounding can leave a tiny negative value where the exact one is 0.
  return std::max(0.0, static_cast<double>(s.sum_squares) - sum_norm / s.area);
}

// The mean colour of every label of a window's segmentation, as doubles (not rounded to
// 8 bits, so that the comparison measures the segmentation, not the rounding).
std::vector<cv::Vec3d> RegionMeans(const cv::Mat& bgr, const cv::Mat& labels) {
  std::vector<cv::Vec3d> sum;
  std::vector<int64_t> area;
  for (int row = 0; row < labels.rows; ++row) {
    const int32_t* label = labels.ptr<int32_t>(row);
    const cv::Vec3b* colour = bgr.ptr<cv::Vec3b>(row);
    for (int col = 0; col < labels.cols; ++col) {
      const int32_t l = label[col];
      ATTEND_CHECK(l >= 0) << "ShiftVariance: the segment function left pixel (" << col << ", "
                           << row << ") unlabelled";
      if (static_cast<size_t>(l) >= sum.size()) {
        sum.resize(static_cast<size_t>(l) + 1, cv::Vec3d(0, 0, 0));
        area.resize(static_cast<size_t>(l) + 1, 0);
      }
      sum[l] += cv::Vec3d(colour[col][0], colour[col][1], colour[col][2]);
      ++area[l];
    }
  }
  for (size_t l = 0; l < sum.size(); ++l) {
    if (area[l] > 0) sum[l] /= static_cast<double>(area[l]);
  }
  return sum;
}

// Runs the segment function on a continuous copy of `window` and checks what it returns.
cv::Mat SegmentWindow(const cv::Mat& window, const SegmentFunction& segment) {
  cv::Mat labels;
  segment(window.clone(), &labels);
  ATTEND_CHECK(labels.type() == CV_32SC1 && labels.size() == window.size())
      << "ShiftVariance: the segment function returned labels of type " << labels.type()
      << " and size " << labels.cols << "x" << labels.rows << " for a window of " << window.cols
      << "x" << window.rows;
  // A clone: a segmenter may hand back a buffer it overwrites on its next call.
  return labels.clone();
}

}  // namespace

SegmentationQuality EvaluateSegmentation(const cv::Mat& bgr, const cv::Mat& labels) {
  CheckImageAndLabels(bgr, labels, "EvaluateSegmentation");
  const std::vector<RegionSums> sums = SumRegions(bgr, labels);

  // N x M is the number of labelled pixels: the whole image unless some labels are < 0.
  int64_t labelled = 0;
  std::vector<int64_t> areas;
  for (const RegionSums& s : sums) {
    if (s.area == 0) continue;
    labelled += s.area;
    areas.push_back(s.area);
  }
  if (labelled == 0) {
    throw InputError("EvaluateSegmentation: no pixel of the " + std::to_string(bgr.cols) + "x" +
                     std::to_string(bgr.rows) + " image is labelled (all labels < 0)");
  }

  // R(A): the number of regions whose area is exactly A, read off the sorted areas.
  std::sort(areas.begin(), areas.end());
  auto regions_of_area = [&areas](int64_t area) {
    const auto range = std::equal_range(areas.begin(), areas.end(), area);
    return static_cast<double>(range.second - range.first);
  };

  double f_sum = 0.0;
  double q_sum = 0.0;
  for (const RegionSums& s : sums) {
    if (s.area == 0) continue;
    const double a = static_cast<double>(s.area);
    const double e2 = SquaredColourError(s);
    f_sum += e2 / std::sqrt(a);  // eq. 3.3
    const double small_regions = regions_of_area(s.area) / a;
    q_sum += e2 / (1.0 + std::log(a)) + small_regions * small_regions;  // eq. 3.4
  }

  SegmentationQuality quality;
  quality.regions = static_cast<int>(areas.size());
  const double sqrt_r = std::sqrt(static_cast<double>(quality.regions));
  const double n_m = static_cast<double>(labelled);
  // Liu and Yang's F with Borsotti's 1/(1000 N M) normalisation (thesis eq. 3.3).
  quality.f = sqrt_r * f_sum / (1000.0 * n_m);
  // Borsotti's Q. The thesis prints 1/1000 in eq. 3.4; SPEC 4 follows Borsotti's 1/10000.
  quality.q = sqrt_r * q_sum / (10000.0 * n_m);
  return quality;
}

double ShiftVariance(const cv::Mat& bgr, const SegmentFunction& segment, int window,
                     int max_shift) {
  ATTEND_CHECK(bgr.type() == CV_8UC3) << "ShiftVariance: image type " << bgr.type();
  ATTEND_CHECK(max_shift >= 1) << "ShiftVariance: max_shift " << max_shift;
  // Every shifted window must share pixels with the first one.
  ATTEND_CHECK(window > max_shift)
      << "ShiftVariance: window " << window << " not larger than max_shift " << max_shift;
  const int span = window + max_shift;
  if (bgr.cols < span || bgr.rows < span) {
    throw InputError("shift variance with a " + std::to_string(window) + "-pixel window and " +
                     std::to_string(max_shift) + "-pixel shifts needs an image of at least " +
                     std::to_string(span) + "x" + std::to_string(span) + " pixels; it is " +
                     std::to_string(bgr.cols) + "x" + std::to_string(bgr.rows));
  }

  // The span x span square that all shifted windows cover is centred in the image; the
  // unshifted window is its top-left corner.
  const int x0 = (bgr.cols - span) / 2;
  const int y0 = (bgr.rows - span) / 2;
  const cv::Mat base_image = bgr(cv::Rect(x0, y0, window, window));
  const cv::Mat base_labels = SegmentWindow(base_image, segment);
  const std::vector<cv::Vec3d> base_means = RegionMeans(base_image, base_labels);

  double rmsd_sum = 0.0;
  int shifts = 0;
  for (int dy = 0; dy <= max_shift; ++dy) {
    for (int dx = 0; dx <= max_shift; ++dx) {
      if (dx == 0 && dy == 0) continue;
      const cv::Mat image = bgr(cv::Rect(x0 + dx, y0 + dy, window, window));
      const cv::Mat labels = SegmentWindow(image, segment);
      const std::vector<cv::Vec3d> means = RegionMeans(image, labels);
      // Scene pixel (x0 + dx + u, y0 + dy + v) is (dx + u, dy + v) in the unshifted window and
      // (u, v) in the shifted one; they share (window - dx) x (window - dy) pixels.
      const int shared_cols = window - dx;
      const int shared_rows = window - dy;
      double sum_d2 = 0.0;
      for (int v = 0; v < shared_rows; ++v) {
        const int32_t* base = base_labels.ptr<int32_t>(dy + v) + dx;
        const int32_t* shifted = labels.ptr<int32_t>(v);
        for (int u = 0; u < shared_cols; ++u) {
          const cv::Vec3d d = base_means[base[u]] - means[shifted[u]];
          sum_d2 += d.dot(d);
        }
      }
      rmsd_sum += std::sqrt(sum_d2 / (static_cast<double>(shared_cols) * shared_rows));  // 3.5
      ++shifts;
    }
  }
  return rmsd_sum / shifts;  // eq. 3.5, over (max_shift + 1)^2 - 1 shifts
}

}  // namespace attend
