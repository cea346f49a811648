// The pre-attentive stage on still images (`attend saliency`): each image on its
// own, as `attend run` computes the first frame of a sequence (the BIP segmentation, the
// feature plugins, their normalised weighted sum), with nothing carried from one image to the
// next. Features that need stereo are left out. Maps come back at the image's own size.
#pragma once

#include <memory>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "features/feature_map.h"
#include "pipeline/attend_options.h"
#include "util/execution_context.h"

namespace attend {

// Where a scanpath's step lands in its attended target (StillSaliency::Compute): the centre of
// the target's box, or the most salient pixel in that box of the map attention selected it on
// (the saliency as the targets before it left it inhibited): where the eyes would go within the
// object attention selected.
enum class ScanpathPoint { kCentre, kPeak };

struct StillMaps {
  cv::Size image_size;    // the input image's
  cv::Size working_size;  // where the maps were computed (sequence.width/height/resize)
  cv::Mat saliency;       // CV_32FC1 at image_size, [0, 1]
  std::vector<std::string> feature_names;
  std::vector<cv::Mat> features;  // each normalised to [0, 1], CV_32FC1 at image_size
  // With `scanpath_steps` > 0: a point of each target attention selects (ScanpathPoint), in the
  // order it selects them (image pixels), and their boxes; the image is shown again as a still
  // frame until that many targets were selected or a frame selects none.
  std::vector<cv::Point2d> scanpath;
  std::vector<cv::Rect> scanpath_boxes;
};

class StillSaliency {
 public:
  // `home`: the folder of bundled files (plugins' relative data paths). ConfigError for
  // features or plugins that cannot be used. `dropped` gets the names of the features left out
  // because they need stereo.
  StillSaliency(const AttendOptions& options, const std::string& home,
                std::vector<std::string>* dropped = nullptr);

  // `bgr`: 8-bit BGR of any size. `with_features`: also return each feature's map.
  StillMaps Compute(const cv::Mat& bgr, bool with_features, int scanpath_steps,
                    ScanpathPoint point = ScanpathPoint::kCentre) const;

 private:
  AttendOptions options_;
  std::string home_;
  FeatureRegistry registry_;  // built-in features and plugins, loaded once
  // The images' pipelines': one pool for all of them (threads as options_.threads).
  std::unique_ptr<ExecutionContext> execution_;
};

}  // namespace attend
