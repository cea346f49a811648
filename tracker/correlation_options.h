// The options of the BIP tracker's correlation mode (TrackerMode::kCorrelation;
// tracker/correlation_tracker.h, docs/TRACKING.md "The correlation mode"): a discriminative
// correlation filter over cell features with a colour model learnt against the target's
// surroundings, scale estimated on its own, a confidence, re-detection over a wider window when
// it falls, and the target's mask from the BIP's regions. The defaults were chosen by
// cross-validation over the OTB sequences (docs/TRACKING.md, "Cross-validation").
#pragma once

#include <string>

#include "util/option_fields.h"

namespace attend {

struct CorrelationOptions {
  // The search window: the target's box grown by `padding` times its mean side in each
  // dimension (a window of w + padding (w + h) / 2 by h + padding (w + h) / 2), resampled to
  // about `window_area` pixels, described by cells of `cell` pixels.
  float padding = 1.0f;
  float window_area = 22500.f;
  int cell = 4;
  // The filter's desired response: a Gaussian of `label_sigma` times the target's mean side
  // (in the window's pixels), in cells. `filter_lambda` regularises the filter, `filter_rate`
  // blends each frame's filter in.
  float label_sigma = 0.0625f;
  float filter_lambda = 1e-3f;
  float filter_rate = 0.01f;
  // Learn from the search's own window and features, the desired response moved to where the
  // target was found in them (as ECO does), instead of sampling the window again at the new
  // position: a third less work a frame.
  bool reuse_search = true;
  // The colour model: per-pixel target likelihood f / (f + b) from histograms of the target
  // (its box shrunk by `inner_padding` of its mean side) and of the window outside the box,
  // `colour_bins` bins per BGR channel, blended in by `colour_rate`. Its response (the mean
  // likelihood over a box of the target's size) counts `colour_share` of the combined
  // response, the filter's the rest.
  float colour_share = 0.5f;
  float colour_rate = 0.04f;
  int colour_bins = 32;
  float inner_padding = 0.2f;
  // Scale (DSST): `scales` samples of the target `scale_step` apart, each resampled to about
  // `scale_area` pixels; the scale filter is blended in by `scale_rate`.
  int scales = 33;
  float scale_step = 1.02f;
  float scale_rate = 0.025f;
  float scale_area = 512.f;
  // The scale is estimated (and its filter learnt) every `scale_every` frames found.
  int scale_every = 2;
  // Confidence: a frame whose response peak is under `confidence_ratio` times the running mean
  // of the peaks of the frames found is not trusted: nothing is learnt from it, a wider window
  // (`redetect_windows` windows each way around the last position, half a window apart) is
  // searched, and when nothing there reaches the bar the target is reported occluded at its
  // last box; after `missed_frames` such frames in a row it is lost. 0: always trusted.
  float confidence_ratio = 0.3f;
  // A frame found whose peak is under `learn_ratio` times the running mean peak of the frames
  // learnt from, or whose response's sharpness (APCE) is under `learn_sharpness` times theirs,
  // moves the box but teaches nothing (Wang et al., CVPR 2017); 0: always learnt from.
  float learn_ratio = 0.f;
  float learn_sharpness = 0.f;
  int redetect_windows = 1;
  // A frame whose peak is under `search_ratio` times the running mean (but trusted) is searched
  // over the wider window too, and goes where the peak is highest; 0: only untrusted frames.
  float search_ratio = 0.f;
  int missed_frames = 30;
  // Motion: the window is placed at the last position plus this share of the last
  // displacement (0: at the last position).
  float motion = 0.f;
  // The mask (thesis 4.2.4 in spirit): the regions of a BIP over-segmentation of the box whose
  // mean colour likelihood is at least this; 0: the whole box.
  float mask_likelihood = 0.5f;

  // "" when valid; otherwise names the field and the broken constraint.
  std::string Check() const;
  static const OptionFields<CorrelationOptions>& Fields();
};

}  // namespace attend
