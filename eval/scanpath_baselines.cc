#include "eval/scanpath_baselines.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "util/error.h"

namespace attend {

Scanpath CentreBiasScanpath(cv::Size image, int count, double duration_s, cv::RNG* rng,
                            double sigma_fraction) {
  ATTEND_CHECK(image.width > 0 && image.height > 0 && count >= 0 && sigma_fraction > 0.0);
  // The centre of the image in 0-based pixels, as CentreBias puts it.
  const double cx = (image.width - 1) / 2.0, cy = (image.height - 1) / 2.0;
  Scanpath path;
  while (static_cast<int>(path.size()) < count) {
    Fixation f;
    f.x = cx + rng->gaussian(sigma_fraction * image.width);
    f.y = cy + rng->gaussian(sigma_fraction * image.height);
    f.duration_s = duration_s;
    // The image spans [-0.5, size - 0.5) in 0-based pixels.
    if (f.x < -0.5 || f.y < -0.5 || f.x >= image.width - 0.5 || f.y >= image.height - 0.5) {
      continue;
    }
    path.push_back(f);
  }
  return path;
}

Scanpath SaliencyPeaks(const cv::Mat& map, cv::Size image, int count, double separation,
                       double duration_s) {
  ATTEND_CHECK(!map.empty() && map.channels() == 1 && count >= 1 && separation >= 0.0);
  cv::Mat values;
  map.convertTo(values, CV_32F);
  const int radius =
      static_cast<int>(std::lround(separation * std::max(values.cols, values.rows)));
  cv::Mat local_max;
  cv::dilate(values, local_max,
             cv::getStructuringElement(cv::MORPH_RECT, {2 * radius + 1, 2 * radius + 1}));
  struct Candidate {
    float value;
    int index;  // raster order
  };
  std::vector<Candidate> candidates;
  for (int y = 0; y < values.rows; ++y) {
    const float* row = values.ptr<float>(y);
    const float* top = local_max.ptr<float>(y);
    for (int x = 0; x < values.cols; ++x) {
      if (row[x] >= top[x]) candidates.push_back({row[x], y * values.cols + x});
    }
  }
  // Highest first; equal heights in raster order.
  std::stable_sort(candidates.begin(), candidates.end(),
                   [](const Candidate& a, const Candidate& b) { return a.value > b.value; });
  std::vector<cv::Point> taken;
  for (const Candidate& c : candidates) {
    if (static_cast<int>(taken.size()) == count) break;
    const cv::Point at(c.index % values.cols, c.index / values.cols);
    const bool near = std::any_of(taken.begin(), taken.end(), [&](const cv::Point& p) {
      return std::max(std::abs(p.x - at.x), std::abs(p.y - at.y)) <= radius;
    });
    if (!near) taken.push_back(at);
  }
  // From the map's pixel centres to the image's.
  const double sx = static_cast<double>(image.width) / values.cols;
  const double sy = static_cast<double>(image.height) / values.rows;
  Scanpath path;
  for (const cv::Point& p : taken) {
    Fixation f;
    f.x = (p.x + 0.5) * sx - 0.5;
    f.y = (p.y + 0.5) * sy - 0.5;
    f.duration_s = duration_s;
    path.push_back(f);
  }
  return path;
}

}  // namespace attend
