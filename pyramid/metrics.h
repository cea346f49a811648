// Quality measures of a segmentation (thesis 3.3.2, SPEC 4). Smaller is better for all.
// docs/PYRAMID.md gives the exact formulas and their sources.
#pragma once

#include <functional>
#include <opencv2/core.hpp>

namespace attend {

struct SegmentationQuality {
  int regions = 0;
  double f = 0.0;  // Liu and Yang's F, normalised as in Borsotti et al. 1998
  double q = 0.0;  // Borsotti, Campadelli and Schettini's Q (1998)
};

// F and Q of `labels` (CV_32SC1, region indices >= 0; pixels < 0 are ignored) over the 8-bit
// BGR image it segments. Colour errors are Euclidean distances in RGB (0..255).
SegmentationQuality EvaluateSegmentation(const cv::Mat& bgr, const cv::Mat& labels);

// Segments an 8-bit BGR image into labels (CV_32SC1).
using SegmentFunction = std::function<void(const cv::Mat& bgr, cv::Mat* labels)>;

// Shift variance (thesis eq. 3.5): the mean, over the shifts (dx, dy) in [0, max_shift]^2
// except (0, 0), of the RMS difference between the region-mean-colour images of the window of
// `window` x `window` pixels at the image centre and of the window shifted by (dx, dy),
// compared on the pixels the two windows share. Needs an image of at least window + max_shift
// pixels each way.
double ShiftVariance(const cv::Mat& bgr, const SegmentFunction& segment, int window = 128,
                     int max_shift = 10);

}  // namespace attend
