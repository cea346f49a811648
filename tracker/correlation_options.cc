#include "tracker/correlation_options.h"

namespace attend {

const OptionFields<CorrelationOptions>& CorrelationOptions::Fields() {
  using O = CorrelationOptions;
  static const OptionFields<CorrelationOptions> fields = {
      {"padding", &O::padding, Range::Closed(0, 10),
       "correlation: the search window is the box grown by this many mean sides"},
      {"window_area", &O::window_area, Range::Closed(256, 1e6),
       "correlation: the window is resampled to about this many pixels"},
      {"cell", &O::cell, Range::Closed(1, 16), "correlation: the features' cell side, pixels"},
      {"label_sigma", &O::label_sigma, Range::Closed(0.001, 1),
       "correlation: the desired response's sigma, in mean sides of the target"},
      {"filter_lambda", &O::filter_lambda, Range::Closed(1e-9, 100),
       "correlation: the filter's regularisation"},
      {"filter_rate", &O::filter_rate, Range::Closed(0, 1),
       "correlation: the filter's update rate"},
      {"reuse_search", &O::reuse_search,
       "correlation: learn from the search's window, not one sampled again"},
      {"colour_share", &O::colour_share, Range::Closed(0, 1),
       "correlation: the colour model's share of the combined response"},
      {"colour_rate", &O::colour_rate, Range::Closed(0, 1),
       "correlation: the colour histograms' update rate"},
      {"colour_bins", &O::colour_bins, Range::Closed(2, 64),
       "correlation: colour histogram bins per channel"},
      {"inner_padding", &O::inner_padding, Range::Closed(0, 0.9),
       "correlation: the target's histogram skips this share of its mean side at the border"},
      {"scales", &O::scales, Range::Closed(1, 129), "correlation: scale samples (DSST)"},
      {"scale_step", &O::scale_step, Range::Closed(1, 2),
       "correlation: the factor between scale samples"},
      {"scale_rate", &O::scale_rate, Range::Closed(0, 1),
       "correlation: the scale filter's update rate"},
      {"scale_area", &O::scale_area, Range::Closed(16, 1e5),
       "correlation: each scale sample is resampled to about this many pixels"},
      {"scale_every", &O::scale_every, Range::Closed(1, 100),
       "correlation: the scale is estimated every this many frames found"},
      {"confidence_ratio", &O::confidence_ratio, Range::Closed(0, 1),
       "correlation: a peak under this share of the mean found peak is not trusted; 0: off"},
      {"learn_ratio", &O::learn_ratio, Range::Closed(0, 1),
       "correlation: a peak under this share of the mean learnt peak teaches nothing; 0: off"},
      {"learn_sharpness", &O::learn_sharpness, Range::Closed(0, 1),
       "correlation: nor does a response under this share of the mean sharpness (APCE)"},
      {"redetect_windows", &O::redetect_windows, Range::Closed(0, 8),
       "correlation: an untrusted frame is searched this many half windows each way"},
      {"search_ratio", &O::search_ratio, Range::Closed(0, 1),
       "correlation: a peak under this share of the mean is searched for wider too; 0: off"},
      {"missed_frames", &O::missed_frames, Range::Closed(1, 1e6),
       "correlation: this many untrusted frames in a row lose the target"},
      {"motion", &O::motion, Range::Closed(0, 1),
       "correlation: the window leads by this share of the last displacement"},
      {"mask_likelihood", &O::mask_likelihood, Range::Closed(0, 1),
       "correlation: mask regions need this mean colour likelihood; 0: the whole box"}};
  return fields;
}

std::string CorrelationOptions::Check() const {
  const std::string error = CheckFieldRanges(*this, Fields());
  if (!error.empty()) return error;
  if (scales % 2 == 0) return "scales must be odd (the middle sample is the current scale)";
  return "";
}

}  // namespace attend
