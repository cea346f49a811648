// Semi-global matching (stereo/semi_global.h, `smoothness: sgm`): the aggregator against a
// direct implementation of Hirschmüller's recursion on random cost volumes, and the estimator
// on stereograms whose disparities are known by construction.
#include "stereo/semi_global.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <opencv2/core.hpp>
#include <random>
#include <vector>

#include "stereo/disparity.h"
#include "util/error.h"

namespace attend {
namespace {

// The sums S(p, d) of the paths `directions` (each (dx, dy): the path comes from
// (x - dx, y - dy)), computed as the recursion reads: a pixel whose predecessor is outside
// the image has L = C.
std::vector<int> ReferenceSums(const std::vector<int>& cost, int width, int height, int depth,
                               const std::vector<cv::Point>& directions, int p1, int p2) {
  std::vector<int> sums(cost.size(), 0);
  auto at = [&](int x, int y, int d) { return (static_cast<size_t>(y) * width + x) * depth + d; };
  for (const cv::Point& r : directions) {
    std::vector<int> paths(cost.size(), 0);
    for (int i = 0; i < height; ++i) {
      const int y = r.y >= 0 ? i : height - 1 - i;
      for (int j = 0; j < width; ++j) {
        const int x = r.x >= 0 ? j : width - 1 - j;
        const int px = x - r.x, py = y - r.y;
        const bool inside = px >= 0 && px < width && py >= 0 && py < height;
        int least = 0;
        if (inside) {
          least = paths[at(px, py, 0)];
          for (int d = 1; d < depth; ++d) least = std::min(least, paths[at(px, py, d)]);
        }
        for (int d = 0; d < depth; ++d) {
          int value = cost[at(x, y, d)];
          if (inside) {
            int best = std::min(paths[at(px, py, d)], least + p2);
            if (d > 0) best = std::min(best, paths[at(px, py, d - 1)] + p1);
            if (d + 1 < depth) best = std::min(best, paths[at(px, py, d + 1)] + p1);
            value += best - least;
          }
          paths[at(x, y, d)] = value;
          sums[at(x, y, d)] += value;
        }
      }
    }
  }
  return sums;
}

struct Maps {
  cv::Mat left, right;
};

// Winner-take-all on the sums: the smallest d of the least sum; the right view along
// S(xr + d, d).
Maps ReferenceMaps(const std::vector<int>& sums, int width, int height, int depth) {
  Maps maps{cv::Mat(height, width, CV_32FC1), cv::Mat(height, width, CV_32FC1)};
  auto at = [&](int x, int y, int d) { return (static_cast<size_t>(y) * width + x) * depth + d; };
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      int best = 0;
      for (int d = 1; d < depth; ++d) {
        if (sums[at(x, y, d)] < sums[at(x, y, best)]) best = d;
      }
      maps.left.at<float>(y, x) = static_cast<float>(best);
      int right_best = 0;
      for (int d = 1; d < depth && x + d < width; ++d) {
        if (sums[at(x + d, y, d)] < sums[at(x + right_best, y, right_best)]) right_best = d;
      }
      maps.right.at<float>(y, x) = static_cast<float>(right_best);
    }
  }
  return maps;
}

TEST(SemiGlobal, AggregatorEqualsTheRecursionOnRandomVolumes) {
  const std::vector<cv::Point> eight = {{1, 0},  {-1, 0}, {0, 1},  {0, -1},
                                        {1, 1},  {-1, -1}, {-1, 1}, {1, -1}};
  const std::vector<cv::Point> five = {{1, 0}, {0, 1}, {1, 1}, {-1, 1}, {-1, 0}};
  std::mt19937 random(11);
  int compared = 0;
  for (const int paths : {8, 5}) {
    for (const int depth : {1, 7, 16, 20, 33}) {
      const int width = 23, height = 9;
      // Costs drawn from a narrow range, so that the penalties decide many pixels, with a
      // smooth trend so that neighbours agree; some ties.
      std::vector<int> cost(static_cast<size_t>(width) * height * depth);
      std::uniform_int_distribution<int> noise(0, 60);
      for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
          const int trend = (x / 4 + y / 3) % depth;
          for (int d = 0; d < depth; ++d) {
            const int value = 20 * std::abs(d - trend) + noise(random);
            cost[(static_cast<size_t>(y) * width + x) * depth + d] =
                std::min(value, SemiGlobalAggregator::kMaxCost);
          }
        }
      }
      for (const auto& [p1, p2] : std::vector<std::pair<int, int>>{{10, 120}, {0, 0}, {76, 317}}) {
        SemiGlobalAggregator aggregator;
        SemiGlobalAggregator::Setup setup;
        setup.width = width;
        setup.height = height;
        setup.depth = depth;
        setup.paths = paths;
        setup.p1 = p1;
        setup.p2 = p2;
        cv::Mat left, right;
        aggregator.Begin(setup, &left, &right);
        for (int y = 0; y < height; ++y) {
          uint8_t* row = aggregator.cost_row(y);
          for (int x = 0; x < width; ++x) {
            for (int d = 0; d < depth; ++d) {
              row[static_cast<size_t>(x) * aggregator.stride() + d] = static_cast<uint8_t>(
                  cost[(static_cast<size_t>(y) * width + x) * depth + d]);
            }
          }
          aggregator.EndRow(y);
        }
        aggregator.Finish();
        const Maps expected = ReferenceMaps(
            ReferenceSums(cost, width, height, depth, paths == 8 ? eight : five, p1, p2), width,
            height, depth);
        const std::string what = std::to_string(paths) + " paths, depth " +
                                 std::to_string(depth) + ", P1 " + std::to_string(p1) + ", P2 " +
                                 std::to_string(p2);
        EXPECT_EQ(cv::norm(left, expected.left, cv::NORM_INF), 0.0) << what;
        EXPECT_EQ(cv::norm(right, expected.right, cv::NORM_INF), 0.0) << what;
        ++compared;
      }
    }
  }
  EXPECT_EQ(compared, 30);
}

// A random-dot pair: disparity 3 everywhere, 9 in a square; the left pixel (x, y) shows the
// right pixel (x - d, y).
struct Pair {
  cv::Mat left, right, truth;
};

Pair SquareStereogram() {
  Pair pair;
  pair.truth = cv::Mat(90, 130, CV_32FC1, cv::Scalar(3.f));
  pair.truth(cv::Rect(50, 30, 40, 30)).setTo(9.f);
  pair.right.create(pair.truth.size(), CV_8UC1);
  cv::RNG rng(4);
  rng.fill(pair.right, cv::RNG::UNIFORM, 0, 256);
  pair.left.create(pair.truth.size(), CV_8UC1);
  for (int y = 0; y < pair.truth.rows; ++y) {
    for (int x = 0; x < pair.truth.cols; ++x) {
      const int source = x - static_cast<int>(pair.truth.at<float>(y, x));
      pair.left.at<uchar>(y, x) = pair.right.at<uchar>(y, std::max(0, source));
    }
  }
  return pair;
}

TEST(SemiGlobal, EstimatorFindsTheSquareExactlyWithSharpEdges) {
  const Pair pair = SquareStereogram();
  for (const int paths : {5, 8}) {
    DisparityOptions options;
    options.smoothness = DisparitySmoothness::kSgm;
    options.sgm_paths = paths;
    options.max_disparity = 16;
    options.window = 5;
    options.median = 5;
    DisparityEstimator estimator(options);
    cv::Mat disparity;
    estimator.Compute(pair.left, pair.right, &disparity);
    int wrong = 0, known = 0;
    // Everything but a band of four pixels around the square's edges (two where the 5-pixel
    // window straddles the edge, and up to two more where the paths from the background carry
    // its disparity over before paying the jump P2) and the image's left strip (x < 9, no
    // match). The occluded band left of the square (left pixels whose right pixels the square
    // hides) is in: the check and the fill must give it the background's 3.
    for (int y = 2; y < disparity.rows - 2; ++y) {
      for (int x = 9; x < disparity.cols - 2; ++x) {
        const bool near_edge = ((std::abs(x - 50) <= 4 || std::abs(x - 89) <= 4) && y >= 26 &&
                                y <= 63) ||
                               ((std::abs(y - 30) <= 4 || std::abs(y - 59) <= 4) && x >= 46 &&
                                x <= 93);
        if (near_edge) continue;
        ++known;
        const bool off = disparity.at<float>(y, x) != pair.truth.at<float>(y, x);
        wrong += off;
        if (off) ADD_FAILURE() << x << "," << y << ": " << disparity.at<float>(y, x);
      }
    }
    EXPECT_GT(known, 9000);
    EXPECT_EQ(wrong, 0) << paths << " paths";
  }
}

TEST(SemiGlobal, OptionsOutOfRangeAreConfigurationErrors) {
  DisparityOptions options;
  options.smoothness = DisparitySmoothness::kSgm;
  options.sgm_p1 = 2.f;
  options.sgm_p2 = 1.f;
  EXPECT_NE(options.Check().find("sgm_p2 must be at least sgm_p1"), std::string::npos);
  EXPECT_THROW(DisparityEstimator{options}, ConfigError);
  options.sgm_p1 = 0.5f;
  options.sgm_paths = 6;
  EXPECT_NE(options.Check().find("sgm_paths must be 5 or 8"), std::string::npos);
  options.sgm_paths = 5;
  options.median = 4;
  EXPECT_NE(options.Check().find("median must be 0, 3 or 5"), std::string::npos);
  options.median = 3;
  EXPECT_EQ(options.Check(), "");
}

}  // namespace
}  // namespace attend
