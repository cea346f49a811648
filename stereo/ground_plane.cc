#include "stereo/ground_plane.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "util/error.h"

namespace attend {

namespace {

// A row's share of the width that must be measured at its mode for the row to count.
constexpr double kMinRowShare = 0.1;
// A row's mode is on a line when within this many pixels, plus kModeRelative of it: a mode is
// the mean of a row's values within a bin of it, sharper than a pixel's value, and a looser
// bound lets a wall leaning back pass for ground.
constexpr double kModeTolerance = 0.5;
constexpr double kModeRelative = 0.05;
// The least slope of a ground line (disparity pixels per row): a camera 30 times higher than
// its baseline (a pair 10 cm apart 3 m above the ground) still has 0.033.
constexpr double kMinSlope = 0.02;
// The inlier rows must span this share of the image's height and hold this share of its pixels.
constexpr double kMinSpan = 0.15;
constexpr double kMinSupport = 0.03;
constexpr int kIterations = 200;
// The ground is the surface nearest the camera's feet: a line must explain at least this share
// of the weight of the lowest kBottomRows of the measured rows (a mattress or a wall leaning
// back also grows in disparity downwards, but stops where the floor begins).
constexpr double kBottomRows = 0.2;
constexpr double kBottomShare = 0.5;
constexpr uint64_t kSeed = 0x9e3779b97f4a7c15ULL;

struct RowMode {
  double v = 0.0;
  double d = 0.0;      // the mean of the measured values within a bin of the row's mode
  int weight = 0;      // those values' count
};

// Each row's mode of the measured disparities (bins of 1 px), for the rows measured enough.
std::vector<RowMode> RowModes(const cv::Mat& disparity, const cv::Mat& measured) {
  double max_value = 0.0;
  cv::minMaxLoc(disparity, nullptr, &max_value, nullptr, nullptr, measured);
  const int bins = static_cast<int>(std::ceil(std::max(0.0, max_value))) + 2;
  std::vector<int> histogram(bins);
  std::vector<RowMode> modes;
  for (int y = 0; y < disparity.rows; ++y) {
    const float* d = disparity.ptr<float>(y);
    const uint8_t* m = measured.ptr<uint8_t>(y);
    std::fill(histogram.begin(), histogram.end(), 0);
    for (int x = 0; x < disparity.cols; ++x) {
      if (m[x] && d[x] >= 0.f) ++histogram[static_cast<int>(d[x])];
    }
    // The window of three bins with the most values, and the mean of its values.
    int best = 0, best_count = -1;
    for (int b = 0; b + 2 < bins; ++b) {
      const int count = histogram[b] + histogram[b + 1] + histogram[b + 2];
      if (count > best_count) best = b, best_count = count;
    }
    if (best_count < kMinRowShare * disparity.cols) continue;
    double sum = 0.0;
    for (int x = 0; x < disparity.cols; ++x) {
      if (m[x] && d[x] >= best && d[x] < best + 3) sum += d[x];
    }
    modes.push_back({static_cast<double>(y), sum / best_count, best_count});
  }
  return modes;
}

bool NearLine(const RowMode& mode, double slope, double intercept) {
  const double predicted = slope * mode.v + intercept;
  return std::abs(mode.d - predicted) <= kModeTolerance + kModeRelative * std::max(0.0, predicted);
}

// The weighted least-squares line d = slope v + intercept through the modes near the line
// given; false when they do not determine one.
bool Refine(const std::vector<RowMode>& modes, double* slope, double* intercept) {
  double sw = 0, sv = 0, sd = 0, svv = 0, svd = 0;
  for (const RowMode& mode : modes) {
    if (!NearLine(mode, *slope, *intercept)) continue;
    const double w = mode.weight;
    sw += w, sv += w * mode.v, sd += w * mode.d, svv += w * mode.v * mode.v;
    svd += w * mode.v * mode.d;
  }
  const double det = sw * svv - sv * sv;
  if (sw <= 0.0 || std::abs(det) < 1e-9) return false;
  *slope = (sw * svd - sv * sd) / det;
  *intercept = (sd - *slope * sv) / sw;
  return true;
}

}  // namespace

bool GroundPlane::OnGround(double v, double d) const {
  if (!valid || v <= horizon_v) return false;
  const double ground = DisparityAt(v);
  return std::abs(d - ground) <= kPixelTolerance + kRelativeTolerance * ground;
}

GroundPlane FitGroundPlane(const cv::Mat& disparity, const cv::Mat& measured) {
  ATTEND_CHECK(disparity.type() == CV_32FC1 && measured.type() == CV_8UC1 &&
               disparity.size() == measured.size())
      << "FitGroundPlane takes a float disparity map and an 8-bit mask of its size";
  GroundPlane plane;
  const std::vector<RowMode> modes = RowModes(disparity, measured);
  if (modes.size() < 2) return plane;
  cv::RNG rng(kSeed);
  double best_score = 0.0, best_slope = 0.0, best_intercept = 0.0;
  const int n = static_cast<int>(modes.size());
  // The modes are in row order: the lowest rows are the last.
  const int bottom_from = n - std::max(1, static_cast<int>(kBottomRows * n));
  double bottom_weight = 0.0;
  for (int k = bottom_from; k < n; ++k) bottom_weight += modes[k].weight;
  for (int iteration = 0; iteration < kIterations; ++iteration) {
    const RowMode& a = modes[rng.uniform(0, n)];
    const RowMode& b = modes[rng.uniform(0, n)];
    if (std::abs(a.v - b.v) < 2.0) continue;
    const double slope = (b.d - a.d) / (b.v - a.v);
    if (slope < kMinSlope) continue;
    const double intercept = a.d - slope * a.v;
    double score = 0.0, bottom = 0.0;
    for (int k = 0; k < n; ++k) {
      if (!NearLine(modes[k], slope, intercept)) continue;
      score += modes[k].weight;
      if (k >= bottom_from) bottom += modes[k].weight;
    }
    if (bottom < kBottomShare * bottom_weight) continue;
    if (score > best_score) best_score = score, best_slope = slope, best_intercept = intercept;
  }
  if (best_score <= 0.0 || !Refine(modes, &best_slope, &best_intercept) ||
      best_slope < kMinSlope) {
    return plane;
  }
  double top = disparity.rows, bottom = -1.0;
  int support = 0;
  for (const RowMode& mode : modes) {
    if (!NearLine(mode, best_slope, best_intercept)) continue;
    top = std::min(top, mode.v), bottom = std::max(bottom, mode.v);
    support += mode.weight;
  }
  plane.slope = best_slope;
  plane.horizon_v = -best_intercept / best_slope;
  plane.support = support;
  plane.valid = bottom - top >= kMinSpan * disparity.rows &&
                support >= kMinSupport * disparity.total() && plane.horizon_v < disparity.rows;
  return plane;
}

cv::Mat GroundMask(const cv::Mat& disparity, const cv::Mat& measured, const GroundPlane& ground) {
  cv::Mat mask(disparity.size(), CV_8UC1, cv::Scalar(0));
  if (!ground.valid) return mask;
  for (int y = 0; y < disparity.rows; ++y) {
    const float* d = disparity.ptr<float>(y);
    const uint8_t* m = measured.ptr<uint8_t>(y);
    uint8_t* out = mask.ptr<uint8_t>(y);
    for (int x = 0; x < disparity.cols; ++x) {
      if (m[x] && ground.OnGround(y, d[x])) out[x] = 255;
    }
  }
  return mask;
}

}  // namespace attend
