// One-to-one assignment: the Kuhn-Munkres solver and the box matching built on it, used where
// targets meet boxes (the MOTChallenge match of `attend eval`, the attention stage's match of
// its targets to the detections of a frame).
#pragma once

#include <utility>
#include <vector>

#include <opencv2/core.hpp>

namespace attend {

// The assignment of rows to columns of `cost` (rows of equal length, finite values) that
// minimises the summed cost of the chosen cells (Kuhn-Munkres, the O(n^2 m) form with row and
// column potentials). Every row gets a column when there are at most as many rows as columns,
// every column a row otherwise. Returns each row's column, -1 for a row left without one.
std::vector<int> MinimumCostAssignment(const std::vector<std::vector<double>>& cost);

// The one-to-one pairs (index in `a`, index in `b`) with IoU >= `threshold` that the
// minimum-cost assignment on 1 - IoU picks: as many pairs as there can be, then the least
// summed 1 - IoU. A pair below the threshold costs more than any assignment of valid pairs can
// (each costs < 1, at most min(|a|, |b|) of them).
std::vector<std::pair<int, int>> MatchBoxes(const std::vector<cv::Rect>& a,
                                            const std::vector<cv::Rect>& b, double threshold);
std::vector<std::pair<int, int>> MatchBoxes(const std::vector<cv::Rect2d>& a,
                                            const std::vector<cv::Rect2d>& b, double threshold);

}  // namespace attend
