#include "app/estimate_disparity.h"

#include "app/region_disparity.h"
#include "eval/disparity_scores.h"
#include "io/disparity_files.h"
#include "util/error.h"

namespace attend {

namespace {

std::string SizeText(const cv::Mat& image) {
  return std::to_string(image.cols) + "x" + std::to_string(image.rows);
}

}  // namespace

nlohmann::json EstimateDisparity(const DisparityRequest& request) {
  const DisparityOptions& options = request.options;
  // Every input is read and checked before anything is computed or written.
  const cv::Mat left = ReadStereoImage(request.left);
  const cv::Mat right = ReadStereoImage(request.right);
  if (left.size() != right.size()) {
    throw InputError(request.left + " is " + SizeText(left) + " but " + request.right + " is " +
                     SizeText(right) + "; a stereo pair must have one size");
  }
  if (options.max_disparity >= left.cols) {
    throw InputError(request.left + ": the images are " + SizeText(left) +
                     "; the disparity range 0.." + std::to_string(options.max_disparity - 1) +
                     " (max_disparity " + std::to_string(options.max_disparity) +
                     ") must be below the width " + std::to_string(left.cols));
  }
  cv::Mat ground_truth;
  if (!request.gt.empty()) {
    ground_truth = ReadDisparityGroundTruth(request.gt, request.gt_scale);
    if (ground_truth.size() != left.size()) {
      throw InputError(request.gt + ": the ground truth is " + SizeText(ground_truth) + " but " +
                       request.left + " is " + SizeText(left));
    }
  }

  DisparityEstimator estimator(options);
  cv::Mat disparity;
  estimator.Compute(left, right, &disparity);
  ATTEND_CHECK(disparity.type() == CV_32FC1 && disparity.size() == left.size())
      << "the estimator returned type " << disparity.type() << " of " << SizeText(disparity);
  WriteDisparityMap(request.out, disparity);

  nlohmann::json report = {{"left", request.left},
                           {"right", request.right},
                           {"out", request.out},
                           {"width", left.cols},
                           {"height", left.rows},
                           {"milliseconds", estimator.milliseconds()},
                           {"buffer_bytes", estimator.buffer_bytes()},
                           {"options",
                            {{"max_disparity", options.max_disparity},
                             {"window", options.window},
                             {"subpixel", options.subpixel},
                             {"left_right_check", options.left_right_check},
                             {"lr_tolerance", options.lr_tolerance},
                             {"smoothness", DisparitySmoothnessName(options.smoothness)},
                             {"jump_penalty", options.jump_penalty},
                             {"sgm_p1", options.sgm_p1},
                             {"sgm_p2", options.sgm_p2},
                             {"sgm_paths", options.sgm_paths},
                             {"median", options.median},
                             {"max_width", options.max_width}}}};
  if (!ground_truth.empty()) {
    const BadPixelRates rates = EvaluateDisparity(disparity, ground_truth);
    report["gt"] = request.gt;
    report["gt_scale"] = request.gt_scale;
    report["known_pixels"] = rates.known;
    report["bad1"] = rates.bad1;
    report["bad2"] = rates.bad2;
    if (request.regions > 0.0) {
      report["regions"] = ScoreRegionDisparities(left, right, disparity, ground_truth, options,
                                                 request.regions);
    }
  }
  return report;
}

}  // namespace attend
