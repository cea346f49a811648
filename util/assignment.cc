#include "util/assignment.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "util/box.h"
#include "util/error.h"

namespace attend {

namespace {

// Rows no longer than columns (the caller transposes otherwise). Potentials u (rows) and v
// (columns) keep cost - u - v >= 0 with equality on the assigned cells; each row is added by a
// shortest augmenting path over the reduced costs. Index 0 is a virtual column, so rows and
// columns count from 1 inside.
std::vector<int> AssignRowsToColumns(const std::vector<std::vector<double>>& cost) {
  const int n = static_cast<int>(cost.size());
  const int m = static_cast<int>(cost[0].size());
  constexpr double kInfinity = std::numeric_limits<double>::infinity();
  std::vector<double> u(n + 1, 0.0), v(m + 1, 0.0);
  std::vector<int> row_of(m + 1, 0), way(m + 1, 0);
  for (int i = 1; i <= n; ++i) {
    row_of[0] = i;
    int j0 = 0;
    std::vector<double> min_reduced(m + 1, kInfinity);
    std::vector<bool> used(m + 1, false);
    do {
      used[j0] = true;
      const int i0 = row_of[j0];
      double delta = kInfinity;
      int j1 = 0;
      for (int j = 1; j <= m; ++j) {
        if (used[j]) continue;
        const double reduced = cost[i0 - 1][j - 1] - u[i0] - v[j];
        if (reduced < min_reduced[j]) min_reduced[j] = reduced, way[j] = j0;
        if (min_reduced[j] < delta) delta = min_reduced[j], j1 = j;
      }
      ATTEND_CHECK(j1 > 0) << "no free column for row " << i;
      for (int j = 0; j <= m; ++j) {
        if (used[j]) {
          u[row_of[j]] += delta;
          v[j] -= delta;
        } else {
          min_reduced[j] -= delta;
        }
      }
      j0 = j1;
    } while (row_of[j0] != 0);
    do {
      const int j1 = way[j0];
      row_of[j0] = row_of[j1];
      j0 = j1;
    } while (j0 != 0);
  }
  std::vector<int> column_of(n, -1);
  for (int j = 1; j <= m; ++j) {
    if (row_of[j] != 0) column_of[row_of[j] - 1] = j - 1;
  }
  return column_of;
}

template <typename T>
std::vector<std::pair<int, int>> MatchBoxesImpl(const std::vector<cv::Rect_<T>>& a,
                                                const std::vector<cv::Rect_<T>>& b,
                                                double threshold) {
  std::vector<std::pair<int, int>> pairs;
  if (a.empty() || b.empty()) return pairs;
  const double forbidden = static_cast<double>(std::min(a.size(), b.size())) + 1.0;
  std::vector<std::vector<double>> cost(a.size(), std::vector<double>(b.size(), forbidden));
  std::vector<std::vector<double>> iou(a.size(), std::vector<double>(b.size(), 0.0));
  bool any = false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    for (std::size_t j = 0; j < b.size(); ++j) {
      iou[i][j] = BoxIou(a[i], b[j]);
      if (iou[i][j] >= threshold) cost[i][j] = 1.0 - iou[i][j], any = true;
    }
  }
  if (!any) return pairs;
  const std::vector<int> column = MinimumCostAssignment(cost);
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (column[i] >= 0 && iou[i][column[i]] >= threshold) {
      pairs.emplace_back(static_cast<int>(i), column[i]);
    }
  }
  return pairs;
}

}  // namespace

std::vector<int> MinimumCostAssignment(const std::vector<std::vector<double>>& cost) {
  if (cost.empty() || cost[0].empty()) return std::vector<int>(cost.size(), -1);
  const std::size_t columns = cost[0].size();
  for (const std::vector<double>& row : cost) {
    ATTEND_CHECK(row.size() == columns) << "rows of " << row.size() << " and " << columns;
    for (const double value : row) ATTEND_CHECK(std::isfinite(value)) << "cost " << value;
  }
  if (cost.size() <= columns) return AssignRowsToColumns(cost);
  std::vector<std::vector<double>> transposed(columns, std::vector<double>(cost.size()));
  for (std::size_t i = 0; i < cost.size(); ++i) {
    for (std::size_t j = 0; j < columns; ++j) transposed[j][i] = cost[i][j];
  }
  const std::vector<int> row_of_column = AssignRowsToColumns(transposed);
  std::vector<int> column_of_row(cost.size(), -1);
  for (std::size_t j = 0; j < columns; ++j) column_of_row[row_of_column[j]] = static_cast<int>(j);
  return column_of_row;
}

std::vector<std::pair<int, int>> MatchBoxes(const std::vector<cv::Rect>& a,
                                            const std::vector<cv::Rect>& b, double threshold) {
  return MatchBoxesImpl(a, b, threshold);
}

std::vector<std::pair<int, int>> MatchBoxes(const std::vector<cv::Rect2d>& a,
                                            const std::vector<cv::Rect2d>& b, double threshold) {
  return MatchBoxesImpl(a, b, threshold);
}

}  // namespace attend
