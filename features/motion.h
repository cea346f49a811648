// The `motion` plugin: what moves draws attention (Itti's flicker channel; not in the thesis,
// whose pre-attentive stage has no motion channel). The map is the change of the
// luminance against a background made of the previous frames, with the frame-wide part of the
// change (the light, the camera's exposure) and the sensor noise taken out:
//
//   L_t   the luminance (0.299 R + 0.587 G + 0.114 B), smoothed by a Gaussian of `blur` px
//   B_t   the background: B_1 = L_0, B_t+1 = (1 - rate) B_t + rate L_t (rate 1: previous frame)
//   r     = L_t - g B_t - o, with the global gain g and offset o fitted by least squares to a
//           regular sample of pixels (every 3rd pixel of every 3rd row), then refitted on the
//           pixels whose residual is within the noise bound below, o corrected to make the
//           median residual 0: what is left is local change
//   s     = 1.4826 median |r| over the sample (the noise of r; most of a frame does not move)
//   M     = max(0, |r| - max(min_change, noise_factor s)), box-filtered over `window` px, or
//           averaged over each BIP colour region with `per_region`
//
// The first frame, and every frame that does not follow the one before (a new sequence: a
// frame index not above the previous one, or another image size), gives a map of zeros and
// restarts the background from that frame.
#pragma once

#include <memory>
#include <opencv2/core.hpp>

#include "features/feature_map.h"
#include "util/option_fields.h"

namespace attend {

struct MotionOptions {
  double blur = 1.5;          // sigma of the Gaussian on the luminance, px; 0: none
  double rate = 1.0;          // background update rate in (0, 1]; 1: the previous frame
  double min_change = 8.0;    // luminance change always treated as noise, grey levels
  double noise_factor = 3.0;  // change below this many robust noise sigmas is noise
  int window = 9;             // side of the box filter on the change, px, odd; 1: none
  bool per_region = false;    // average the change over each BIP colour region instead
  // "" when valid; otherwise names the field and the broken constraint.
  std::string Check() const;
  // The fields (util/option_fields.h), which Check and the configuration apply.
  static const OptionFields<MotionOptions>& Fields();
};

// The stateful computation behind the plugin, usable without a FrameContext. `segmentation`
// is needed only with per_region (nullptr otherwise).
class MotionDetector {
 public:
  explicit MotionDetector(const MotionOptions& options);
  // `bgr`: 8-bit BGR. Fills `out` (CV_32FC1, bgr's size).
  void Compute(int frame_index, const cv::Mat& bgr, const Segmentation* segmentation,
               cv::Mat* out);
  // The noise sigma s, the gain g and offset o of the last frame (0, 1, 0 on a first frame).
  double last_noise() const { return last_noise_; }
  double last_gain() const { return last_gain_; }
  double last_offset() const { return last_offset_; }

 private:
  MotionOptions options_;
  int previous_index_ = -1;
  double last_noise_ = 0.0, last_gain_ = 1.0, last_offset_ = 0.0;
  cv::Mat grey_, luminance_, background_, residual_, scratch_;
  std::vector<float> sample_, background_sample_, luminance_sample_;
};

// Parameters: the fields of MotionOptions under their names.
std::unique_ptr<FeatureMap> CreateMotionFeature(const ParamBlock& params,
                                                const FeatureSetup& setup);

}  // namespace attend
