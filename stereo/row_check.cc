#include "stereo/row_check.h"

#include <algorithm>
#include <cmath>
#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>
#include <vector>

namespace attend {

namespace {

constexpr int kFeatures = 2000;
constexpr float kRatio = 0.8f;  // Lowe's ratio test on the two best Hamming distances
constexpr int kPatchRadius = 7;   // the 15 x 15 left patch correlated in the right view
// Rows around the feature match's, and columns beyond the band of disparities: wide enough to
// see a repeat of the texture.
constexpr int kSearchRadius = 16;
constexpr double kMinCorrelation = 0.8;
// A match whose patch correlates nearly as well elsewhere in the search (outside the peak's
// 5 x 5 neighbourhood) is ambiguous: a chessboard's square, an edge along itself.
constexpr double kMaxSecondPeak = 0.9;
// The matches' row shifts are fitted by dy = a + b x + c y (a shift, a turn, a change of
// scale between the views): RANSAC over this many samples of three, inliers within this many
// pixels. Repeated texture (a chessboard) matches many features to the wrong repeat, a whole
// square up or down; the fit leaves them out.
constexpr int kSamples = 300;
constexpr double kInlierPx = 1.0;

struct Shift {
  double x, y;    // the left point
  double dy;      // y_right - y_left
};

// The inliers of the best fit of dy = a + b x + c y to `shifts` (all when there are fewer
// than four: nothing to fit); `outliers` gets the others.
std::vector<Shift> ConsistentShifts(const std::vector<Shift>& shifts,
                                    std::vector<Shift>* outliers) {
  outliers->clear();
  if (shifts.size() < 4) return shifts;
  cv::RNG rng(0x5eed);  // deterministic: the same pair gives the same verdict
  const int n = static_cast<int>(shifts.size());
  std::vector<char> best_inliers;
  int best_count = 0;
  for (int sample = 0; sample < kSamples; ++sample) {
    const int i = rng.uniform(0, n), j = rng.uniform(0, n), k = rng.uniform(0, n);
    if (i == j || j == k || i == k) continue;
    const cv::Matx33d A(1, shifts[i].x, shifts[i].y, 1, shifts[j].x, shifts[j].y, 1, shifts[k].x,
                        shifts[k].y);
    const cv::Vec3d b(shifts[i].dy, shifts[j].dy, shifts[k].dy);
    if (std::abs(cv::determinant(A)) < 1e-6) continue;
    const cv::Vec3d model = A.solve(b, cv::DECOMP_LU);
    std::vector<char> inliers(n, 0);
    int count = 0;
    for (int m = 0; m < n; ++m) {
      const Shift& s = shifts[m];
      if (std::abs(model[0] + model[1] * s.x + model[2] * s.y - s.dy) <= kInlierPx) {
        inliers[m] = 1;
        ++count;
      }
    }
    if (count > best_count) {
      best_count = count;
      best_inliers = std::move(inliers);
    }
  }
  std::vector<Shift> kept;
  for (int m = 0; m < n; ++m) {
    (!best_inliers.empty() && best_inliers[m] ? kept : *outliers).push_back(shifts[m]);
  }
  return kept;
}

cv::Mat Grey(const cv::Mat& image) {
  if (image.channels() == 1) return image;
  cv::Mat grey;
  cv::cvtColor(image, grey, image.channels() == 4 ? cv::COLOR_BGRA2GRAY : cv::COLOR_BGR2GRAY);
  return grey;
}

// The offset of the vertex of the parabola through (-1, a), (0, b), (1, c) from 0.
double ParabolaVertex(double a, double b, double c) {
  const double curvature = a - 2.0 * b + c;
  return curvature < 0.0 ? 0.5 * (a - c) / curvature : 0.0;
}

double Median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  const size_t middle = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + middle, values.end());
  double median = values[middle];
  if (values.size() % 2 == 0) {
    median = 0.5 * (median + *std::max_element(values.begin(), values.begin() + middle));
  }
  return median;
}

// The feature match refined: the left patch around `at_left` (rounded) correlated over a band
// of the right view, the rows around `at_right`'s and every column from the left point's
// (disparity 0, less the search radius) to a third of the image to its left. False when the
// patch or the band's rows leave an image, or the peak is weak, on the band's edge or not
// unique in the band. `shift` gets right minus left, sub-pixel.
bool RefineMatch(const cv::Mat& left, const cv::Mat& right, cv::Point2f at_left,
                 cv::Point2f at_right, cv::Point2d* shift) {
  const cv::Point left_centre(cvRound(at_left.x), cvRound(at_left.y));
  const int right_row = cvRound(at_right.y);
  const int side = 2 * kPatchRadius + 1;
  const cv::Rect patch(left_centre.x - kPatchRadius, left_centre.y - kPatchRadius, side, side);
  if ((patch & cv::Rect(0, 0, left.cols, left.rows)) != patch) return false;
  const int reach = kPatchRadius + kSearchRadius;
  const int first_column = std::max(0, left_centre.x - right.cols / 3 - reach);
  const int last_column = std::min(right.cols - 1, left_centre.x + reach);
  const cv::Rect band(first_column, right_row - reach, last_column - first_column + 1,
                      2 * reach + 1);
  if (band.width < side || (band & cv::Rect(0, 0, right.cols, right.rows)) != band) return false;
  cv::Mat scores;
  cv::matchTemplate(right(band), left(patch), scores, cv::TM_CCOEFF_NORMED);
  double best = 0.0;
  cv::Point peak;
  cv::minMaxLoc(scores, nullptr, &best, nullptr, &peak);
  if (!(best >= kMinCorrelation) || peak.x == 0 || peak.y == 0 || peak.x == scores.cols - 1 ||
      peak.y == scores.rows - 1) {
    return false;
  }
  cv::Mat others = scores.clone();
  others(cv::Rect(peak.x - 2, peak.y - 2, 5, 5) & cv::Rect(0, 0, others.cols, others.rows))
      .setTo(-1.0f);
  double second = 0.0;
  cv::minMaxLoc(others, nullptr, &second);
  if (second >= kMaxSecondPeak * best) return false;
  const auto s = [&](int x, int y) { return static_cast<double>(scores.at<float>(y, x)); };
  const double dx = ParabolaVertex(s(peak.x - 1, peak.y), s(peak.x, peak.y), s(peak.x + 1, peak.y));
  const double dy = ParabolaVertex(s(peak.x, peak.y - 1), s(peak.x, peak.y), s(peak.x, peak.y + 1));
  shift->x = band.x + kPatchRadius + peak.x + dx - left_centre.x;
  shift->y = band.y + kPatchRadius + peak.y + dy - left_centre.y;
  return true;
}

}  // namespace

RowCheck MeasureRowOffset(const cv::Mat& left_image, const cv::Mat& right_image) {
  RowCheck check;
  if (left_image.empty() || right_image.empty()) return check;
  const cv::Mat left = Grey(left_image), right = Grey(right_image);
  cv::Ptr<cv::ORB> orb = cv::ORB::create(kFeatures);
  std::vector<cv::KeyPoint> left_points, right_points;
  cv::Mat left_descriptors, right_descriptors;
  orb->detectAndCompute(left, cv::noArray(), left_points, left_descriptors);
  orb->detectAndCompute(right, cv::noArray(), right_points, right_descriptors);
  if (left_points.size() < 2 || right_points.size() < 2) return check;

  cv::BFMatcher matcher(cv::NORM_HAMMING);
  std::vector<std::vector<cv::DMatch>> forward;
  std::vector<cv::DMatch> backward;
  matcher.knnMatch(left_descriptors, right_descriptors, forward, 2);
  matcher.match(right_descriptors, left_descriptors, backward);
  std::vector<Shift> matched;
  for (const std::vector<cv::DMatch>& pair : forward) {
    if (pair.size() < 2 || pair[0].distance >= kRatio * pair[1].distance) continue;
    const cv::DMatch& m = pair[0];
    if (backward[m.trainIdx].trainIdx != m.queryIdx) continue;  // not mutual
    cv::Point2d shift;
    if (!RefineMatch(left, right, left_points[m.queryIdx].pt, right_points[m.trainIdx].pt,
                     &shift)) {
      continue;
    }
    // Disparity -shift.x must be >= 0 (half a pixel of noise allowed) and within the image.
    if (shift.x > 0.5 || -shift.x >= left.cols) continue;
    const cv::Point2f& at = left_points[m.queryIdx].pt;
    matched.push_back({at.x, at.y, shift.y});
  }
  // Repeated texture may support a second shift as well as the true one (a chessboard's
  // features matched a square off, all alike): of two well-supported fits the one with the
  // smaller offset stands, so that a pair is refused only when every fit it supports is off.
  std::vector<Shift> rest, unused;
  const std::vector<Shift> first = ConsistentShifts(matched, &rest);
  const std::vector<Shift> second = ConsistentShifts(rest, &unused);
  const auto measure = [](const std::vector<Shift>& inliers) {
    RowCheck fit;
    std::vector<double> offsets, shifts;
    for (const Shift& s : inliers) {
      offsets.push_back(std::abs(s.dy));
      shifts.push_back(s.dy);
    }
    fit.matches = static_cast<int>(inliers.size());
    fit.row_offset_px = Median(offsets);
    fit.row_shift_px = Median(shifts);
    return fit;
  };
  check = measure(first);
  const bool supported = second.size() >= std::max<size_t>(kMinRowMatches, first.size() / 2);
  if (supported) {
    const RowCheck other = measure(second);
    if (other.row_offset_px < check.row_offset_px) check = other;
  }
  return check;
}

}  // namespace attend
