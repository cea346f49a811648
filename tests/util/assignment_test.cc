// One-to-one assignment (util/assignment.h): the solver on matrices whose optimum is known
// (and against brute force), and the box match on boxes whose pairs are worked out by hand.
#include "util/assignment.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <numeric>
#include <random>
#include <utility>
#include <vector>

namespace attend {
namespace {

double AssignedCost(const std::vector<std::vector<double>>& cost,
                    const std::vector<int>& column_of_row) {
  double total = 0.0;
  for (std::size_t i = 0; i < column_of_row.size(); ++i) {
    if (column_of_row[i] >= 0) total += cost[i][column_of_row[i]];
  }
  return total;
}

// The least cost of any assignment, trying every injective map of the shorter side into the
// longer one.
double BruteForceMinimum(const std::vector<std::vector<double>>& cost) {
  const int rows = static_cast<int>(cost.size());
  const int columns = static_cast<int>(cost[0].size());
  const int longer = std::max(rows, columns);
  std::vector<int> order(longer);
  std::iota(order.begin(), order.end(), 0);
  double best = std::numeric_limits<double>::infinity();
  do {
    double total = 0.0;
    if (rows <= columns) {
      for (int i = 0; i < rows; ++i) total += cost[i][order[i]];
    } else {
      for (int j = 0; j < columns; ++j) total += cost[order[j]][j];
    }
    best = std::min(best, total);
  } while (std::next_permutation(order.begin(), order.end()));
  return best;
}

// ------------------------------------------------------------------------------------------
// MinimumCostAssignment

TEST(MinimumCostAssignment, SquareMatrixWithAUniqueOptimum) {
  // 1 + 2 + 2 = 5; the other five permutations cost 6, 9, 7, 6 and 11.
  const std::vector<std::vector<double>> cost = {{4, 1, 3}, {2, 0, 5}, {3, 2, 2}};
  EXPECT_EQ(MinimumCostAssignment(cost), (std::vector<int>{1, 0, 2}));
}

TEST(MinimumCostAssignment, BeatsTheGreedyChoice) {
  // Greedy takes the cheapest cell (1) and is left with 100; the optimum is 2 + 2.
  const std::vector<std::vector<double>> cost = {{1, 2}, {2, 100}};
  EXPECT_EQ(MinimumCostAssignment(cost), (std::vector<int>{1, 0}));
}

TEST(MinimumCostAssignment, MoreColumnsThanRowsGivesEveryRowAColumn) {
  // r0 -> c1 (1) and r1 -> c2 (1); c0 stays free.
  const std::vector<std::vector<double>> cost = {{3, 1, 2}, {4, 2, 1}};
  EXPECT_EQ(MinimumCostAssignment(cost), (std::vector<int>{1, 2}));
}

TEST(MinimumCostAssignment, MoreRowsThanColumnsLeavesARowOut) {
  // Two of three rows: r0 -> c1 (4) and r1 -> c0 (2) = 6, against 9, 10, 7, 11, 11 for the
  // other choices; greedy would start with r0 -> c0 (1) and reach 9.
  const std::vector<std::vector<double>> cost = {{1, 4}, {2, 8}, {3, 9}};
  EXPECT_EQ(MinimumCostAssignment(cost), (std::vector<int>{1, 0, -1}));
}

TEST(MinimumCostAssignment, EmptyMatricesAssignNothing) {
  EXPECT_TRUE(MinimumCostAssignment({}).empty());
  EXPECT_EQ(MinimumCostAssignment({{}, {}}), (std::vector<int>{-1, -1}));
}

TEST(MinimumCostAssignment, MatchesBruteForceOnRandomMatrices) {
  std::mt19937 random(7);
  std::uniform_int_distribution<int> value(-20, 50);
  const std::vector<std::pair<int, int>> shapes = {{1, 1}, {1, 5}, {5, 1}, {4, 4}, {5, 5},
                                                   {3, 6}, {6, 3}, {2, 7}, {7, 7}};
  for (const auto& [rows, columns] : shapes) {
    for (int trial = 0; trial < 20; ++trial) {
      std::vector<std::vector<double>> cost(rows, std::vector<double>(columns));
      for (auto& row : cost) {
        for (double& cell : row) cell = value(random);
      }
      const std::vector<int> column = MinimumCostAssignment(cost);
      SCOPED_TRACE(::testing::Message() << rows << "x" << columns << " trial " << trial);
      ASSERT_EQ(column.size(), static_cast<std::size_t>(rows));
      // One to one, and as many pairs as the shorter side.
      std::vector<int> assigned;
      for (const int j : column) {
        if (j >= 0) assigned.push_back(j);
      }
      EXPECT_EQ(static_cast<int>(assigned.size()), std::min(rows, columns));
      std::sort(assigned.begin(), assigned.end());
      EXPECT_EQ(std::adjacent_find(assigned.begin(), assigned.end()), assigned.end());
      EXPECT_DOUBLE_EQ(AssignedCost(cost, column), BruteForceMinimum(cost));
    }
  }
}

// ------------------------------------------------------------------------------------------
// MatchBoxes

TEST(MatchBoxes, TakesAsManyPairsAsThereCanBeThenTheBestOverlaps) {
  // Boxes 10 high on one row, so IoU is the overlap of the x intervals over their union:
  // a0 [0, 10) - b0 [1, 11) 9/11, a0 - b1 [-3, 7) 7/13, a1 [6, 16) - b0 5/15, a1 - b1 1/19.
  // Greedy on IoU pairs a0 with b0 and leaves a1 alone; the match pairs a0-b1 and a1-b0.
  const std::vector<cv::Rect> a = {cv::Rect(0, 0, 10, 10), cv::Rect(6, 0, 10, 10)};
  const std::vector<cv::Rect> b = {cv::Rect(1, 0, 10, 10), cv::Rect(-3, 0, 10, 10)};
  EXPECT_EQ(MatchBoxes(a, b, 0.3), (std::vector<std::pair<int, int>>{{0, 1}, {1, 0}}));
  // At 0.5 only a0's two pairs remain, and the better one is taken.
  EXPECT_EQ(MatchBoxes(a, b, 0.5), (std::vector<std::pair<int, int>>{{0, 0}}));
}

TEST(MatchBoxes, LeavesPairsBelowTheThresholdOut) {
  const std::vector<cv::Rect2d> a = {cv::Rect2d(0, 0, 10, 10), cv::Rect2d(100, 0, 10, 10)};
  const std::vector<cv::Rect2d> b = {cv::Rect2d(5, 0, 10, 10), cv::Rect2d(100, 0, 10, 10)};
  // IoU(a0, b0) = 50 / 150 = 1/3, IoU(a1, b1) = 1.
  EXPECT_EQ(MatchBoxes(a, b, 0.5), (std::vector<std::pair<int, int>>{{1, 1}}));
  EXPECT_EQ(MatchBoxes(a, b, 0.3), (std::vector<std::pair<int, int>>{{0, 0}, {1, 1}}));
  EXPECT_TRUE(MatchBoxes(a, {}, 0.3).empty());
}

}  // namespace
}  // namespace attend
