// Detections as a channel's map (features/detectors.h): each painted as a filled box or a
// Gaussian over its box, and what the channels share about their detections: non-maximum
// suppression and a score's confidence.
#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "features/feature_map.h"

namespace attend {

// How a detection is painted into its channel's map: its box filled with its value, or a
// Gaussian over the box (centred across it and at `centre_y` of its height from the top, sigma
// `sigma` times its width and height, peak its value), which is highest where people look on a
// face or a body and falls off towards its edges.
enum class DetectionShape { kBox, kGaussian };

struct DetectionPaint {
  DetectionShape shape = DetectionShape::kBox;
  double sigma = 0.5;     // gaussian: share of the box's width and height
  double centre_y = 0.5;  // gaussian: the centre's height in the box, share from its top
  // Each detection's value is its confidence times (its box's height / the map's height) to
  // this power; 0: the confidence alone.
  double size_power = 0.0;
  double blur = 0.0;  // sigma of a Gaussian on the whole map, share of the larger side; 0: none
};

// The map of `detections` (CV_32FC1 of `size`): each painted as `paint` says (the maximum where
// they overlap), 0 elsewhere, then blurred as `paint.blur` says.
void PaintDetections(const std::vector<Detection>& detections, const DetectionPaint& paint,
                     cv::Size size, cv::Mat* map);

// Greedy non-maximum suppression: the most confident first, then each box whose IoU with a
// kept box of the same label exceeds `max_iou` is dropped. Keeps the order of confidence.
void SuppressOverlaps(double max_iou, std::vector<Detection>* detections);

// A monotone map of a detector's score (an SVM margin, a cascade's final stage sum) into
// (0, 1]: the logistic function, 0.5 at a score of 0.
float ScoreToConfidence(double score);

}  // namespace attend
