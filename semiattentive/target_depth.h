// Each attended target's disparity in a stereo run (thesis 5.2.2.1; docs/STEREO3D.md), two
// ways, with its uncertainty:
//   template  the thesis's: the target's pixels in the left frame are a template (eq. 5.3, 5.4:
//             no memory of earlier frames, weight 1 on every pixel) shifted along its rows in
//             the right frame; the overlap at a shift is the share of template pixels whose
//             colour matches (the sum over B, G, R of |left - right| at most
//             depth.match_tolerance); the best shift is refined by a parabola through its
//             overlap and its two neighbours';
//   map       a robust statistic of the frame's disparity map over the target's mask: the
//             mean of the values between its quartiles (the interquartile mean), which is
//             sub-pixel even where the map is integer. The map is the disparity feature's; a
//             run without that feature measures by the template.
// Either is then filtered over the frames by a fourth-order low-pass filter (a Butterworth,
// two biquads, started at the first value so that it has no transient), as the thesis filters
// its estimates; depth.low_pass is its cutoff as a fraction of the frame rate, >= 0.5 none.
//
// Uncertainty (the standard deviation reported, docs/STEREO3D.md measures how well it covers
// the errors): template, the sub-pixel peak's from the overlap's binomial noise over the
// template's independent samples (one per window x window pixels) and the peak's curvature;
// map, the interquartile mean's from the values' spread (1.4826 MAD) over the same independent
// samples; each combined with the spread of the frame's raw values around the filtered series
// (a running mean of the squared difference), which covers motion in depth and outliers.
#pragma once

#include <limits>
#include <map>
#include <opencv2/core.hpp>
#include <string_view>

#include "stereo/ground_plane.h"
#include "util/enum_table.h"
#include "util/option_fields.h"

namespace attend {

enum class TargetDisparityMethod { kOff, kTemplate, kMap };
inline constexpr EnumTable<TargetDisparityMethod, 3> kTargetDisparityMethods = {{{
    {TargetDisparityMethod::kOff, "off"},
    {TargetDisparityMethod::kTemplate, "template"},
    {TargetDisparityMethod::kMap, "map"},
}}};

// The configuration's `depth:` section.
struct DepthOptions {
  // How each target's disparity is estimated on a stereo run; off: not at all.
  // map is the more accurate on the real pairs and on the rendered scenes (docs/STEREO3D.md).
  TargetDisparityMethod method = TargetDisparityMethod::kMap;
  // template: a template pixel matches the right image's pixel when the sum over B, G, R of
  // their absolute differences is at most this (8-bit values).
  float match_tolerance = 30.f;
  // The fourth-order low-pass filter's cutoff, a fraction of the frame rate; 0.5 or more: none.
  float low_pass = 0.25f;
  // The pixels of the template (or of the mask) read, at most: a larger target is read on a
  // regular grid of about this many (its estimate then costs no more than a smaller one's).
  int max_samples = 4096;

  // Depth in the loop (0: off): a candidate whose disparity differs by more than
  // `separate_px` from that of the target it overlaps is not that target's;
  float separate_px = 0.f;
  // a found target whose raw disparity leaves its filtered one by more than `jump_px` is a
  // switch to another object, and is released ("depth_jump"); the test is always on the
  // thesis's template estimate, filtered at `jump_low_pass` (the cutoff it was chosen with;
  // low_pass, the recorded estimate's, may differ), whatever `method` records (it measured
  // best so on the rendered scenes, docs/STEREO3D.md; the map's jumped on its own noise), and
  // a move within three of the raw estimate's standard deviations is not a jump;
  float jump_px = 3.f;
  float jump_low_pass = 0.1f;
  // a target inhibits only the pixels whose disparity is within `inhibit_band_px` of its own
  // (an object passing in front of it is not inhibited by it).
  float inhibit_band_px = 0.f;
  // map: only the pixels where the disparity was measured (StereoInput::measured) count, and a
  // target with less than this share of its mask measured has no disparity (nor position) in
  // that frame, recorded as "depth_missing": "unmeasured". 0: every pixel, the filled ones too
  // (as before; the sky then got a position at 30-75 m).
  float min_measured = 0.2f;

  std::string Check() const;
  static const OptionFields<DepthOptions>& Fields();
};

// A disparity in working pixels with its standard deviation; NaN when there is none.
struct DisparityEstimate {
  double disparity = std::numeric_limits<double>::quiet_NaN();
  double sd = std::numeric_limits<double>::quiet_NaN();
  // Not valid because too few of the target's pixels were measured (DepthOptions::min_measured).
  bool unmeasured = false;
  bool valid() const { return disparity == disparity; }
};

// The thesis's estimate of the target `mask` (CV_8UC1, the frame's size, within `box`) of
// `left` in `right` (8-bit BGR), shifts 0 .. max_disparity - 1. `window`: the side of the
// patch whose pixels are counted as one independent sample. Invalid when the mask is empty or
// no shift overlaps at all.
DisparityEstimate TemplateDisparity(const cv::Mat& left, const cv::Mat& right, const cv::Mat& mask,
                                    const cv::Rect& box, int max_disparity,
                                    const DepthOptions& options, int window);
// The interquartile mean of `disparity` (CV_32FC1; values < 0 are invalid and left out) over
// `mask` within `box`. Invalid when no valid value is under the mask. With `measured` (CV_8UC1,
// 255 where the disparity was measured) and options.min_measured > 0, only the measured pixels
// count, and the estimate is invalid and `unmeasured` when fewer than min_measured of the
// mask's pixels are.
DisparityEstimate MapDisparity(const cv::Mat& disparity, const cv::Mat& mask, const cv::Rect& box,
                               const DepthOptions& options, int window,
                               const cv::Mat& measured = cv::Mat());

// A fourth-order Butterworth low-pass filter (two biquads by the bilinear transform); cutoff a
// fraction of the sampling rate, in (0, 0.5); the first value starts it in its steady state.
class LowPass4 {
 public:
  explicit LowPass4(double cutoff);
  double Step(double x);
  // The sum of the squares of its impulse response: the share of white noise's variance
  // that passes.
  double NoiseGain() const { return noise_gain_; }

 private:
  struct Biquad {
    double b0 = 1, b1 = 0, b2 = 0, a1 = 0, a2 = 0;
    double x1 = 0, x2 = 0, y1 = 0, y2 = 0;
    double Step(double x);
  };
  Biquad stages_[2];
  bool started_ = false;
  double noise_gain_ = 1.0;
};

// A point of the rectified left camera's frame (X right, Y down, Z forward), metres, with the
// standard deviation of each coordinate.
struct Position3d {
  cv::Vec3d m;
  cv::Vec3d sd_m;
};
// The position of the pixel `centroid` at disparity `disparity` (pixels of the same image) for
// a rectified pair of focal length `focal_px`, principal point (cx, cy) and baseline
// `baseline_m`: Z = f B / d, X = (u - cx) Z / f, Y = (v - cy) Z / f; each coordinate's standard
// deviation from the disparity's (first order: |coordinate| sd_d / d). False (and nothing
// written) when the disparity is invalid or not above 0.
bool Triangulate(double focal_px, double cx, double cy, double baseline_m, cv::Point2d centroid,
                 const DisparityEstimate& disparity, Position3d* position);

// What the stereo pair gives the attention stage in a frame.
struct StereoInput {
  cv::Mat right;      // 8-bit BGR, the working size; empty on a monocular frame
  cv::Mat disparity;  // CV_32FC1, the frame's disparity map (method map, inhibit_band_px)
  // CV_8UC1, 255 where the disparity was measured (DisparityEstimator::measured); empty when
  // unknown (every pixel counts).
  cv::Mat measured;
  GroundPlane ground;  // of `disparity` over `measured` (not valid without them)
  int max_disparity = 0;  // the disparities searched, at the working size
  int window = 5;         // the disparity's matching window
  bool empty() const { return right.empty(); }
};

// Each target's disparity over the frames: the estimate of each frame, filtered.
class TargetDepths {
 public:
  explicit TargetDepths(const DepthOptions& options) : options_(options) {}
  bool enabled() const { return options_.method != TargetDisparityMethod::kOff; }

  // This frame's raw estimate of the target on `mask`, not yet filtered.
  DisparityEstimate Measure(const cv::Mat& left, const StereoInput& stereo, const cv::Mat& mask,
                            const cv::Rect& box) const;
  // Target `id`'s filtered disparity after the frame's raw estimate `raw` (its last one when
  // `raw` is invalid).
  DisparityEstimate Update(int id, const DisparityEstimate& raw);
  // Its last filtered disparity (invalid when it has none).
  DisparityEstimate Last(int id) const;
  // depth.jump_px: how far the template estimate of target `id` on `mask` leaves its filtered
  // series beyond three of its own standard deviations (0 when it has no series yet, or moves
  // less), which then takes the estimate in. `raw` is this frame's
  // estimate when `method` is template (measured already), ignored otherwise.
  double JumpOf(int id, const cv::Mat& left, const StereoInput& stereo, const cv::Mat& mask,
                const cv::Rect& box, const DisparityEstimate& raw);
  void Forget(int id) {
    tracks_.erase(id);
    jumps_.erase(id);
  }

 private:
  struct Track {
    explicit Track(double cutoff) : filter(cutoff) {}
    LowPass4 filter;
    double spread2 = 0.0;  // running mean of (raw - filtered)^2
    int frames = 0;
    DisparityEstimate last;
  };
  // The template's series for the jump test.
  struct JumpTrack {
    explicit JumpTrack(double cutoff) : filter(cutoff) {}
    LowPass4 filter;
    double last = 0.0;
  };
  std::map<int, JumpTrack> jumps_;
  DepthOptions options_;
  std::map<int, Track> tracks_;
};

}  // namespace attend
