// One target of the correlation tracker (tracker/correlation_tracker.h): its filters, colour
// model, position, scale and confidence, and one frame's search. Not part of the API.
#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "tracker/colour_likelihood.h"
#include "tracker/correlation_filter.h"
#include "tracker/correlation_options.h"
#include "tracker/hog_features.h"
#include "tracker/tracker_options.h"

namespace attend {
namespace tracker_internal {

class CorrelationTarget {
 public:
  // Learns the target in `box` of `frame` (8-bit BGR; the box inside the frame, not empty).
  CorrelationTarget(const CorrelationOptions& options, const cv::Mat& frame, const cv::Rect& box);

  // Searches `frame`; returns the state (found, occluded, or lost after missed_frames
  // untrusted frames in a row).
  TrackState Track(const cv::Mat& frame);

  // The box (rounded and clipped to the last frame), the position and size behind it.
  cv::Rect box() const { return box_; }
  cv::Point2d centre() const { return centre_; }
  cv::Size2d size() const { return base_size_ * scale_; }
  // The last response peak and the running mean of the trusted ones.
  double peak() const { return peak_; }
  double mean_peak() const { return mean_peak_; }
  // Per pixel of `patch` (8-bit BGR), the colour model's likelihood of the target.
  cv::Mat Likelihood(const cv::Mat& patch) const {
    cv::Mat likelihood;
    colour_.Likelihood(patch, &likelihood);
    return likelihood;
  }

 private:
  struct Search {
    cv::Point2d centre;  // the target's centre it found, frame pixels
    double peak = 0.0;   // the combined response there
    double sharpness = 0.0;  // the response's APCE
    cv::Point2d offset;      // the peak's offset from the window's centre, cells
  };
  // The window of the current scale centred at `centre`, resampled to the model's size.
  // (A view of a buffer the next call overwrites.)
  // `actual`: where its centre is (the position may be rounded to whole pixels).
  const cv::Mat& Window(const cv::Mat& frame, const cv::Point2d& centre,
                        cv::Point2d* actual = nullptr);
  // The combined response over the window centred at `centre` and its best position.
  Search SearchAt(const cv::Mat& frame, const cv::Point2d& centre);
  // Searches windows around `centre`, half a window apart (redetect_windows each way).
  Search SearchWider(const cv::Mat& frame, const cv::Point2d& centre);
  // The scale samples around `centre`: one column of features per scale factor.
  cv::Mat ScaleSamples(const cv::Mat& frame, const cv::Point2d& centre);
  // Learns the filters and the colour model at the current position and scale; the scale
  // filter from `scale_samples` (taken at the current scale).
  void Learn(const cv::Mat& frame, const cv::Mat& scale_samples, double filter_rate,
             double colour_rate, double scale_rate);
  // As Learn, from the last search's window and features (patch_ and the filter's last
  // spectra), the target at `offset` cells from the window's centre.
  void LearnFromSearch(const cv::Point2d& offset, const cv::Mat& scale_samples);
  // The colour model from `patch`, a window whose target is `offset` model pixels from its centre.
  void LearnColour(const cv::Mat& patch, const cv::Point2d& offset, double rate);
  void UpdateBox(cv::Size frame_size);

  CorrelationOptions options_;
  cv::Size2d base_size_;       // the target's size at scale 1, frame pixels
  cv::Size2d window_base_;     // the window's size at scale 1, frame pixels
  cv::Size model_window_;      // the window resampled, pixels (whole cells)
  cv::Point2d model_factor_;   // model pixels per frame pixel at scale 1, x and y
  cv::Size target_model_;      // the target in the window's pixels
  cv::Size scale_model_;       // a scale sample's size, pixels (whole cells)
  std::vector<double> scale_factors_;
  double min_scale_ = 0.0, max_scale_ = 0.0;

  TranslationFilter filter_;
  ScaleFilter scale_filter_;
  ColourLikelihood colour_;
  HogCells hog_;
  // Buffers kept between calls.
  std::vector<cv::Mat> channels_;
  cv::Mat patch_, border_, likelihood_, scale_patch_;

  cv::Point2d centre_;
  cv::Point2d velocity_;
  double scale_ = 1.0;
  cv::Rect box_;
  double peak_ = 0.0;
  double mean_peak_ = 0.0;
  double mean_sharpness_ = 0.0;
  int learnt_frames_ = 0;
  int frames_ = 0;  // frames tracked since the start
  int missed_ = 0;
};

}  // namespace tracker_internal
}  // namespace attend
