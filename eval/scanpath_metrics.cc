#include "eval/scanpath_metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "util/error.h"

namespace attend {

namespace {

int CellIndex(double coordinate, int extent, int cells) {
  // Pixel i covers [i - 0.5, i + 0.5): the image spans [-0.5, extent - 0.5).
  const int cell = static_cast<int>(std::floor((coordinate + 0.5) * cells / extent));
  return std::clamp(cell, 0, cells - 1);
}

void CheckGrid(cv::Size image, const ScanpathGrid& grid) {
  ATTEND_CHECK(image.width > 0 && image.height > 0) << image.width << "x" << image.height;
  ATTEND_CHECK(grid.columns > 0 && grid.rows > 0) << grid.columns << "x" << grid.rows;
}

// The median of `values` (the mean of the middle two for an even count), as numpy's.
double ScanpathMedian(std::vector<double> values) {
  ATTEND_CHECK(!values.empty());
  const size_t middle = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + middle, values.end());
  const double upper = values[middle];
  if (values.size() % 2 == 1) return upper;
  return 0.5 * (upper + *std::max_element(values.begin(), values.begin() + middle));
}

// The angle between the directions of two saccades, in [0, pi].
double DirectionDifference(const Saccade& u, const Saccade& v) {
  double difference = std::abs(std::atan2(u.dy, u.dx) - std::atan2(v.dy, v.dx));
  if (difference > std::numbers::pi) difference = 2.0 * std::numbers::pi - difference;
  return difference;
}

// One saccade made of `first` and the one after it: the fixation between them is dropped.
Saccade Merged(const Saccade& first, const Saccade& second) {
  Saccade merged = first;
  merged.dx += second.dx;
  merged.dy += second.dy;
  return merged;
}

// One pass of a simplification rule over the saccades: every pair that `merge` accepts becomes
// one saccade. Returns whether any did.
template <typename Rule>
bool MergePass(std::vector<Saccade>* saccades, Rule merge) {
  bool changed = false;
  for (size_t i = 0; i + 1 < saccades->size();) {
    if (merge((*saccades)[i], (*saccades)[i + 1])) {
      (*saccades)[i] = Merged((*saccades)[i], (*saccades)[i + 1]);
      saccades->erase(saccades->begin() + static_cast<std::ptrdiff_t>(i) + 1);
      changed = true;
    } else {
      ++i;
    }
  }
  return changed;
}

}  // namespace

std::vector<int> GridCodes(const Scanpath& path, cv::Size image, const ScanpathGrid& grid) {
  CheckGrid(image, grid);
  std::vector<int> codes;
  codes.reserve(path.size());
  for (const Fixation& f : path) {
    codes.push_back(CellIndex(f.x, image.width, grid.columns) +
                    grid.columns * CellIndex(f.y, image.height, grid.rows));
  }
  return codes;
}

std::vector<double> SaccadeAmplitudesInCells(const Scanpath& path, cv::Size image,
                                             const ScanpathGrid& grid) {
  CheckGrid(image, grid);
  std::vector<double> amplitudes;
  for (size_t i = 1; i < path.size(); ++i) {
    amplitudes.push_back(std::hypot((path[i].x - path[i - 1].x) * grid.columns / image.width,
                                    (path[i].y - path[i - 1].y) * grid.rows / image.height));
  }
  return amplitudes;
}

double ScanMatchThreshold(const std::vector<double>& amplitudes) {
  ATTEND_CHECK(!amplitudes.empty());
  double mean = 0.0;
  for (const double a : amplitudes) mean += a;
  mean /= static_cast<double>(amplitudes.size());
  double variance = 0.0;
  for (const double a : amplitudes) variance += (a - mean) * (a - mean);
  variance /= static_cast<double>(amplitudes.size());
  return 2.0 * std::sqrt(variance);
}

bool ScanMatchOptions::Check(std::string* error) const {
  if (grid.columns < 1 || grid.rows < 1) {
    *error = "grid: columns and rows must be at least 1";
  } else if (!(threshold > 0.0) || !std::isfinite(threshold)) {
    *error = "threshold: must be > 0 (cells)";
  } else if (!(gap <= 0.0)) {
    *error = "gap: must be <= 0";
  } else if (!(temporal_bin_s >= 0.0) || !std::isfinite(temporal_bin_s)) {
    *error = "temporal_bin_s: must be >= 0";
  } else {
    return true;
  }
  return false;
}

double ScanMatchSubstitution(int a, int b, const ScanMatchOptions& options) {
  const int columns = options.grid.columns;
  const double distance = std::hypot(a % columns - b % columns, a / columns - b / columns);
  return options.threshold - distance;
}

std::vector<int> ScanMatchSequence(const Scanpath& path, cv::Size image,
                                   const ScanMatchOptions& options) {
  const std::vector<int> codes = GridCodes(path, image, options.grid);
  if (options.temporal_bin_s <= 0.0) return codes;
  std::vector<int> sequence;
  for (size_t i = 0; i < codes.size(); ++i) {
    ATTEND_CHECK(path[i].duration_s >= 0.0) << "temporal bins need durations";
    const long bins = std::max(1L, std::lround(path[i].duration_s / options.temporal_bin_s));
    sequence.insert(sequence.end(), static_cast<size_t>(bins), codes[i]);
  }
  return sequence;
}

double NeedlemanWunschScore(const std::vector<int>& a, const std::vector<int>& b,
                            const ScanMatchOptions& options) {
  // score[i][j]: the best alignment of a's first i letters with b's first j, one row at a time.
  std::vector<double> previous(b.size() + 1), current(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) previous[j] = options.gap * static_cast<double>(j);
  for (size_t i = 1; i <= a.size(); ++i) {
    current[0] = options.gap * static_cast<double>(i);
    for (size_t j = 1; j <= b.size(); ++j) {
      current[j] = std::max({previous[j - 1] + ScanMatchSubstitution(a[i - 1], b[j - 1], options),
                             previous[j] + options.gap, current[j - 1] + options.gap});
    }
    std::swap(previous, current);
  }
  return previous[b.size()];
}

double ScanMatch(const Scanpath& a, const Scanpath& b, cv::Size image,
                 const ScanMatchOptions& options) {
  std::string error;
  ATTEND_CHECK(options.Check(&error)) << error;
  ATTEND_CHECK(!a.empty() && !b.empty());
  const std::vector<int> sa = ScanMatchSequence(a, image, options);
  const std::vector<int> sb = ScanMatchSequence(b, image, options);
  const double best = options.threshold * static_cast<double>(std::max(sa.size(), sb.size()));
  return NeedlemanWunschScore(sa, sb, options) / best;
}

int CodeEditDistance(const std::vector<int>& a, const std::vector<int>& b) {
  std::vector<int> previous(b.size() + 1), current(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) previous[j] = static_cast<int>(j);
  for (size_t i = 1; i <= a.size(); ++i) {
    current[0] = static_cast<int>(i);
    for (size_t j = 1; j <= b.size(); ++j) {
      current[j] = std::min({previous[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1), previous[j] + 1,
                             current[j - 1] + 1});
    }
    std::swap(previous, current);
  }
  return previous[b.size()];
}

double SequenceScore(const Scanpath& a, const Scanpath& b, cv::Size image,
                     const ScanpathGrid& grid) {
  ATTEND_CHECK(!a.empty() && !b.empty());
  const int distance = CodeEditDistance(GridCodes(a, image, grid), GridCodes(b, image, grid));
  return 1.0 - static_cast<double>(distance) / static_cast<double>(std::max(a.size(), b.size()));
}

bool MultiMatchOptions::Check(std::string* error) const {
  if (!(amplitude_threshold >= 0.0) || !std::isfinite(amplitude_threshold)) {
    *error = "amplitude_threshold: must be >= 0 (share of the diagonal)";
  } else if (!(direction_threshold_deg >= 0.0 && direction_threshold_deg <= 180.0)) {
    *error = "direction_threshold_deg: must be in [0, 180]";
  } else if (!(duration_threshold_s >= 0.0) || !std::isfinite(duration_threshold_s)) {
    *error = "duration_threshold_s: must be >= 0";
  } else {
    return true;
  }
  return false;
}

std::vector<Saccade> SaccadeVectors(const Scanpath& path) {
  std::vector<Saccade> saccades;
  for (size_t i = 1; i < path.size(); ++i) {
    const Fixation& from = path[i - 1];
    saccades.push_back(
        {from.x, from.y, path[i].x - from.x, path[i].y - from.y, from.duration_s});
  }
  return saccades;
}

std::vector<Saccade> SimplifySaccades(std::vector<Saccade> saccades, cv::Size image,
                                      const MultiMatchOptions& options) {
  const double amplitude = options.amplitude_threshold * std::hypot(image.width, image.height);
  const double direction = options.direction_threshold_deg * std::numbers::pi / 180.0;
  // The fixation between two saccades is the second one's start.
  const auto by_direction = [&](const Saccade& u, const Saccade& v) {
    return v.duration_s < options.duration_threshold_s && DirectionDifference(u, v) < direction;
  };
  const auto by_amplitude = [&](const Saccade& u, const Saccade& v) {
    return v.duration_s < options.duration_threshold_s && std::hypot(u.dx, u.dy) < amplitude &&
           std::hypot(v.dx, v.dy) < amplitude;
  };
  // Jarodzka et al. repeat both rules until neither merges anything.
  for (bool changed = true; changed;) {
    const bool direction_merged = MergePass(&saccades, by_direction);
    const bool amplitude_merged = MergePass(&saccades, by_amplitude);
    changed = direction_merged || amplitude_merged;
  }
  return saccades;
}

// Jarodzka et al. find the alignment with Dijkstra's algorithm on the graph whose nodes are
// the matrix's cells, each linked to its right, lower and lower-right neighbour with the
// neighbour's difference as the edge's cost. That graph is a DAG whose edges only go right
// and down, so the cheapest path to every cell is the cheapest path to one of its three
// predecessors plus the cell's cost: this dynamic programme finds exactly Dijkstra's path
// length (ties between equally cheap paths go to the diagonal, then to the step down).
std::vector<std::pair<int, int>> AlignSaccades(const std::vector<Saccade>& a,
                                               const std::vector<Saccade>& b) {
  ATTEND_CHECK(!a.empty() && !b.empty());
  const int n = static_cast<int>(a.size()), m = static_cast<int>(b.size());
  cv::Mat_<double> cost(n, m);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < m; ++j) {
      const double difference = std::hypot(a[i].dx - b[j].dx, a[i].dy - b[j].dy);
      double before = 0.0;
      if (i > 0 || j > 0) {
        const double inf = std::numeric_limits<double>::infinity();
        before = std::min({i > 0 && j > 0 ? cost(i - 1, j - 1) : inf, i > 0 ? cost(i - 1, j) : inf,
                           j > 0 ? cost(i, j - 1) : inf});
      }
      cost(i, j) = difference + before;
    }
  }
  std::vector<std::pair<int, int>> path = {{n - 1, m - 1}};
  for (int i = n - 1, j = m - 1; i > 0 || j > 0;) {
    if (i > 0 && j > 0 && cost(i - 1, j - 1) <= cost(i - 1, j) &&
        cost(i - 1, j - 1) <= cost(i, j - 1)) {
      --i;
      --j;
    } else if (i > 0 && (j == 0 || cost(i - 1, j) <= cost(i, j - 1))) {
      --i;
    } else {
      --j;
    }
    path.emplace_back(i, j);
  }
  std::reverse(path.begin(), path.end());
  return path;
}

std::optional<MultiMatchScores> MultiMatch(const Scanpath& a, const Scanpath& b, cv::Size image,
                                           const MultiMatchOptions& options) {
  std::string error;
  ATTEND_CHECK(options.Check(&error)) << error;
  ATTEND_CHECK(image.width > 0 && image.height > 0);
  if (a.size() < 2 || b.size() < 2) return std::nullopt;
  std::vector<Saccade> u = SaccadeVectors(a), v = SaccadeVectors(b);
  if (options.simplify) {
    u = SimplifySaccades(std::move(u), image, options);
    v = SimplifySaccades(std::move(v), image, options);
  }
  std::vector<double> shape, direction, length, position, duration;
  for (const auto& [i, j] : AlignSaccades(u, v)) {
    shape.push_back(std::hypot(u[i].dx - v[j].dx, u[i].dy - v[j].dy));
    direction.push_back(DirectionDifference(u[i], v[j]));
    length.push_back(std::abs(std::hypot(u[i].dx, u[i].dy) - std::hypot(v[j].dx, v[j].dy)));
    position.push_back(std::hypot(u[i].x - v[j].x, u[i].y - v[j].y));
    const double longer = std::max(u[i].duration_s, v[j].duration_s);
    if (u[i].duration_s < 0.0 || v[j].duration_s < 0.0) {
      duration.push_back(std::numeric_limits<double>::quiet_NaN());
    } else {
      duration.push_back(longer > 0.0 ? std::abs(u[i].duration_s - v[j].duration_s) / longer
                                      : 0.0);
    }
  }
  const double diagonal = std::hypot(image.width, image.height);
  MultiMatchScores scores;
  scores.shape = 1.0 - ScanpathMedian(shape) / (2.0 * diagonal);
  scores.direction = 1.0 - ScanpathMedian(direction) / std::numbers::pi;
  scores.length = 1.0 - ScanpathMedian(length) / diagonal;
  scores.position = 1.0 - ScanpathMedian(position) / diagonal;
  const bool durations_known =
      std::none_of(duration.begin(), duration.end(), [](double d) { return std::isnan(d); });
  scores.duration = durations_known ? 1.0 - ScanpathMedian(duration)
                                    : std::numeric_limits<double>::quiet_NaN();
  return scores;
}

}  // namespace attend
