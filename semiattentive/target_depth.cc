#include "semiattentive/target_depth.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "util/error.h"

namespace attend {

namespace {

// The grid step that reads about `max_samples` of the `pixels` under a mask.
int SampleStep(int pixels, int max_samples) {
  if (pixels <= max_samples) return 1;
  return static_cast<int>(std::ceil(std::sqrt(static_cast<double>(pixels) / max_samples)));
}

// The independent samples among `pixels` read at grid step `step` (one per window x window
// pixels of the image).
double IndependentSamples(int pixels, int step, int window) {
  const double per_sample = std::max(1.0, static_cast<double>(window * window) / (step * step));
  return std::max(1.0, pixels / per_sample);
}

// The mean of the values between the quartiles, and the values' spread (1.4826 MAD).
struct RobustSpread {
  double mean = 0.0;
  double spread = 0.0;
  size_t count = 0;
};

RobustSpread InterquartileMean(std::vector<float> values) {
  std::sort(values.begin(), values.end());
  const size_t count = values.size();
  const size_t low = count / 4, high = std::max(low + 1, count - count / 4);
  double sum = 0.0;
  for (size_t i = low; i < high; ++i) sum += values[i];
  const double median = values[count / 2];
  std::vector<double> deviations(count);
  for (size_t i = 0; i < count; ++i) deviations[i] = std::abs(values[i] - median);
  std::nth_element(deviations.begin(), deviations.begin() + count / 2, deviations.end());
  return {sum / static_cast<double>(high - low), 1.4826 * deviations[count / 2], count};
}

}  // namespace

const OptionFields<DepthOptions>& DepthOptions::Fields() {
  using O = DepthOptions;
  static const OptionFields<DepthOptions> fields = {
      {"method", EnumField<&O::method, kTargetDisparityMethods>(),
       "each target's disparity: template (the thesis's), map (the disparity map's), off"},
      {"match_tolerance", &O::match_tolerance, Range::Closed(0, 765),
       "template: a pixel matches when sum over B, G, R of |left - right| is at most this"},
      {"jump_low_pass", &O::jump_low_pass, Range::Closed(0.01, 1),
       "the jump test's low-pass cutoff, a fraction of the frame rate; >= 0.5: none"},
      {"low_pass", &O::low_pass, Range::Closed(0.01, 1),
       "the 4th-order low-pass cutoff, a fraction of the frame rate; >= 0.5: none"},
      {"max_samples", &O::max_samples, Range::Closed(16, 1e7),
       "pixels of a target read at most (a larger one is read on a grid)"},
      {"separate_px", &O::separate_px, Range::Closed(0, 1000),
       "a candidate this much nearer or farther than the target it overlaps is not it; 0 off"},
      {"jump_px", &O::jump_px, Range::Closed(0, 1000),
       "a target whose disparity jumps this much from its filtered one is released; 0 off"},
      {"inhibit_band_px", &O::inhibit_band_px, Range::Closed(0, 1000),
       "a target inhibits only pixels within this disparity of its own; 0 off"},
      {"min_measured", &O::min_measured, Range::Closed(0, 1),
       "map: a target with less of its mask measured (left-right consistent, textured) has no "
       "disparity and no position; 0: every pixel, the filled ones too"}};
  return fields;
}

std::string DepthOptions::Check() const { return CheckFieldRanges(*this, Fields()); }

namespace {

// The template's samples (every `step`-th pixel of `mask` in `inside`, a box in the image), and
// for each shift d below matches->size() how many of them match the right view at x - d in
// colour (a sum of absolute differences at most `tolerance`) and how many the right view shows
// at that shift (in_view).
int CountMatches(const cv::Mat& left, const cv::Mat& right, const cv::Mat& mask,
                 const cv::Rect& inside, int step, int tolerance, std::vector<int>* matches,
                 std::vector<int>* in_view) {
  const int max_disparity = static_cast<int>(matches->size());
  // The right row's channels in reverse order from column `end` - 1 down, planar: the partners
  // of left pixel x at shifts 0, 1, ... are then consecutive (reversed[end - 1 - x + d]), and
  // the loop over the shifts vectorises.
  const int end = inside.br().x;
  const int begin = std::max(0, inside.x - max_disparity + 1);
  std::vector<uint8_t> reversed(3 * static_cast<size_t>(end - begin));
  const size_t plane = end - begin;
  std::vector<int> last_count(max_disparity, 0);  // samples whose last shift in view is d
  int samples = 0;
  for (int y = inside.y; y < inside.br().y; y += step) {
    const uint8_t* m = mask.ptr<uint8_t>(y);
    const cv::Vec3b* l = left.ptr<cv::Vec3b>(y);
    const cv::Vec3b* r = right.ptr<cv::Vec3b>(y);
    bool loaded = false;
    for (int x = inside.x; x < end; x += step) {
      if (m[x] == 0) continue;
      if (!loaded) {
        for (int c = begin; c < end; ++c) {
          const size_t k = end - 1 - c;
          reversed[k] = r[c][0];
          reversed[plane + k] = r[c][1];
          reversed[2 * plane + k] = r[c][2];
        }
        loaded = true;
      }
      ++samples;
      const int p0 = l[x][0], p1 = l[x][1], p2 = l[x][2];
      const int last = std::min(max_disparity - 1, x);
      ++last_count[last];
      const uint8_t* q0 = &reversed[end - 1 - x];
      const uint8_t* q1 = q0 + plane;
      const uint8_t* q2 = q1 + plane;
      int* match = matches->data();
      for (int d = 0; d <= last; ++d) {
        const int cost = std::abs(p0 - q0[d]) + std::abs(p1 - q1[d]) + std::abs(p2 - q2[d]);
        match[d] += cost <= tolerance;
      }
    }
  }
  // in_view[d]: the samples whose last shift is d or more.
  for (int d = max_disparity - 1, running = 0; d >= 0; --d) {
    running += last_count[d];
    (*in_view)[d] = running;
  }
  return samples;
}

}  // namespace

DisparityEstimate TemplateDisparity(const cv::Mat& left, const cv::Mat& right, const cv::Mat& mask,
                                    const cv::Rect& box, int max_disparity,
                                    const DepthOptions& options, int window) {
  ATTEND_CHECK(left.type() == CV_8UC3 && right.type() == CV_8UC3 && mask.type() == CV_8UC1)
      << "TemplateDisparity takes 8-bit BGR views and an 8-bit mask";
  const cv::Rect inside = box & cv::Rect(0, 0, left.cols, left.rows);
  const int pixels = inside.empty() ? 0 : cv::countNonZero(mask(inside));
  max_disparity = std::min(max_disparity, left.cols);
  if (pixels == 0 || max_disparity < 1) return {};
  const int step = SampleStep(pixels, options.max_samples);
  const int tolerance = static_cast<int>(options.match_tolerance);
  // matches[d]: template pixels whose colour matches at shift d; in_view[d]: those that the
  // right view shows at all (x - d >= 0). A left pixel nearer the left edge than its disparity
  // has no partner: at each shift the overlap is taken over the pixels in view, and a shift
  // that leaves fewer than half of them in view is not tried.
  std::vector<int> matches(max_disparity, 0), in_view(max_disparity, 0);
  const int samples = CountMatches(left, right, mask, inside, step, tolerance, &matches, &in_view);
  if (samples == 0) return {};
  std::vector<double> overlap(max_disparity, -1.0);  // -1: not tried
  int best = -1;
  for (int d = 0; d < max_disparity; ++d) {
    if (2 * in_view[d] < samples) continue;
    overlap[d] = static_cast<double>(matches[d]) / in_view[d];
    if (best < 0 || overlap[d] > overlap[best]) best = d;
  }
  if (best < 0 || overlap[best] <= 0.0) return {};
  const double p0 = overlap[best];
  double offset = 0.0;
  double curvature = 0.0;  // the overlap's second difference at the peak, <= 0
  if (best > 0 && best + 1 < max_disparity && overlap[best - 1] >= 0.0 &&
      overlap[best + 1] >= 0.0) {
    const double minus = overlap[best - 1];
    const double plus = overlap[best + 1];
    curvature = minus - 2.0 * p0 + plus;
    if (curvature < 0.0) offset = std::clamp(0.5 * (minus - plus) / curvature, -0.5, 0.5);
  }
  // The overlaps' binomial noise over the independent samples, through the vertex's formula;
  // a flat peak (no curvature) leaves the shift uncertain by its plateau, a pixel at least.
  const double n = IndependentSamples(samples, step, window);
  const double noise = std::sqrt(std::max(p0 * (1.0 - p0), 1.0 / n) / n);
  double sd = curvature < 0.0 ? noise / (std::numbers::sqrt2 * -curvature) : 1.0;
  sd = std::clamp(sd, 1.0 / std::sqrt(12.0 * n), static_cast<double>(max_disparity));
  return {best + offset, sd};
}

DisparityEstimate MapDisparity(const cv::Mat& disparity, const cv::Mat& mask, const cv::Rect& box,
                               const DepthOptions& options, int window, const cv::Mat& measured) {
  ATTEND_CHECK(disparity.type() == CV_32FC1 && mask.type() == CV_8UC1)
      << "MapDisparity takes a float disparity map and an 8-bit mask";
  const cv::Rect inside = box & cv::Rect(0, 0, disparity.cols, disparity.rows);
  const int pixels = inside.empty() ? 0 : cv::countNonZero(mask(inside));
  if (pixels == 0) return {};
  const bool only_measured = !measured.empty() && options.min_measured > 0.f;
  if (only_measured) {
    // Depth only where it was measured: the filled pixels (sky, blank walls, occlusions) hold
    // the matcher's guess, and a thin object's would be what lies behind it.
    const int seen = cv::countNonZero(mask(inside) & measured(inside));
    if (seen < options.min_measured * pixels || seen == 0) {
      DisparityEstimate none;
      none.unmeasured = true;
      return none;
    }
  }
  const int step = SampleStep(pixels, options.max_samples);
  std::vector<float> values;
  std::vector<int> columns;
  for (int y = inside.y; y < inside.br().y; y += step) {
    const uint8_t* m = mask.ptr<uint8_t>(y);
    const uint8_t* seen = only_measured ? measured.ptr<uint8_t>(y) : nullptr;
    const float* d = disparity.ptr<float>(y);
    for (int x = inside.x; x < inside.br().x; x += step) {
      if (seen != nullptr && seen[x] == 0) continue;
      if (m[x] != 0 && d[x] >= 0.f && std::isfinite(d[x])) {
        values.push_back(d[x]);
        columns.push_back(x);
      }
    }
  }
  if (values.empty()) return {};
  // A left pixel nearer the left edge than its disparity has no partner in the right view, and
  // its value is a guess: once the estimate is known, those pixels are left out and it is made
  // again (where at least a quarter remain).
  RobustSpread estimate = InterquartileMean(values);
  std::vector<float> seen;
  for (size_t i = 0; i < values.size(); ++i) {
    if (columns[i] >= estimate.mean) seen.push_back(values[i]);
  }
  if (seen.size() < values.size() && 4 * seen.size() >= values.size()) {
    estimate = InterquartileMean(seen);
  }
  const size_t count = estimate.count;
  const double mean = estimate.mean, spread = estimate.spread;
  const double n = IndependentSamples(static_cast<int>(count), step, window);
  // The interquartile mean's standard error is about 1.1 sigma / sqrt(n) for normal values;
  // an integer map's rounding (sd 1 / sqrt(12)) stands in for a spread of 0.
  const double sigma = std::max(spread, 1.0 / std::sqrt(12.0));
  return {mean, 1.1 * sigma / std::sqrt(n)};
}

double LowPass4::Biquad::Step(double x) {
  const double y = b0 * x + b1 * x1 + b2 * x2 - a1 * y1 - a2 * y2;
  x2 = x1;
  x1 = x;
  y2 = y1;
  y1 = y;
  return y;
}

LowPass4::LowPass4(double cutoff) {
  if (cutoff >= 0.5) return;  // no filter: both stages pass their input
  ATTEND_CHECK(cutoff > 0.0) << "a low-pass cutoff must be above 0, got " << cutoff;
  // A 4th-order Butterworth: two biquads with the Q of its two pole pairs.
  const double qs[2] = {1.0 / (2.0 * std::cos(std::numbers::pi / 8.0)),
                        1.0 / (2.0 * std::cos(3.0 * std::numbers::pi / 8.0))};
  const double w0 = 2.0 * std::numbers::pi * cutoff;
  for (int s = 0; s < 2; ++s) {
    const double alpha = std::sin(w0) / (2.0 * qs[s]);
    const double a0 = 1.0 + alpha;
    Biquad& b = stages_[s];
    b.b0 = (1.0 - std::cos(w0)) / 2.0 / a0;
    b.b1 = (1.0 - std::cos(w0)) / a0;
    b.b2 = b.b0;
    b.a1 = -2.0 * std::cos(w0) / a0;
    b.a2 = (1.0 - alpha) / a0;
  }
  // The noise gain from the impulse response (it decays well within 2000 samples).
  LowPass4 probe = *this;
  probe.started_ = true;
  double gain = 0.0;
  for (int i = 0; i < 2000; ++i) {
    const double h = probe.Step(i == 0 ? 1.0 : 0.0);
    gain += h * h;
  }
  noise_gain_ = gain;
}

double LowPass4::Step(double x) {
  if (!started_) {
    // The steady state of a constant input x: both stages hold x on both sides (gain 1 at 0).
    for (Biquad& b : stages_) b.x1 = b.x2 = b.y1 = b.y2 = x;
    started_ = true;
  }
  return stages_[1].Step(stages_[0].Step(x));
}

DisparityEstimate TargetDepths::Measure(const cv::Mat& left, const StereoInput& stereo,
                                        const cv::Mat& mask, const cv::Rect& box) const {
  if (!enabled() || stereo.empty() || mask.empty()) return {};
  if (options_.method == TargetDisparityMethod::kTemplate) {
    return TemplateDisparity(left, stereo.right, mask, box, stereo.max_disparity, options_,
                             stereo.window);
  }
  // Without a dense map (a run without the disparity feature), the template measures.
  if (stereo.disparity.empty()) {
    return TemplateDisparity(left, stereo.right, mask, box, stereo.max_disparity, options_,
                             stereo.window);
  }
  return MapDisparity(stereo.disparity, mask, box, options_, stereo.window, stereo.measured);
}

DisparityEstimate TargetDepths::Update(int id, const DisparityEstimate& raw) {
  auto it = tracks_.find(id);
  // Unmeasured this frame: no depth this frame (the filter keeps its state for the next).
  if (raw.unmeasured) return raw;
  if (!raw.valid()) return it == tracks_.end() ? DisparityEstimate{} : it->second.last;
  if (it == tracks_.end()) it = tracks_.emplace(id, Track(options_.low_pass)).first;
  Track& track = it->second;
  const double filtered = track.filter.Step(raw.disparity);
  const double residual = raw.disparity - filtered;
  // The spread's running mean forgets at about the filter's own time scale.
  const double forget = std::clamp(2.0 * options_.low_pass, 0.05, 1.0);
  track.spread2 = track.frames == 0 ? 0.0 : (1.0 - forget) * track.spread2 + forget * residual * residual;
  ++track.frames;
  const double measured2 = raw.sd * raw.sd * track.filter.NoiseGain();
  track.last = {filtered, std::sqrt(measured2 + track.spread2)};
  return track.last;
}

bool Triangulate(double focal_px, double cx, double cy, double baseline_m, cv::Point2d centroid,
                 const DisparityEstimate& disparity, Position3d* position) {
  if (!disparity.valid() || !(disparity.disparity > 0.0) || !(focal_px > 0.0)) return false;
  const double z = focal_px * baseline_m / disparity.disparity;
  const cv::Vec3d m((centroid.x - cx) * z / focal_px, (centroid.y - cy) * z / focal_px, z);
  const double relative = disparity.sd / disparity.disparity;
  position->m = m;
  for (int k = 0; k < 3; ++k) position->sd_m[k] = std::abs(m[k]) * relative;
  return true;
}

double TargetDepths::JumpOf(int id, const cv::Mat& left, const StereoInput& stereo,
                           const cv::Mat& mask, const cv::Rect& box, const DisparityEstimate& raw) {
  if (stereo.empty() || mask.empty()) return 0.0;
  const DisparityEstimate estimate =
      options_.method == TargetDisparityMethod::kTemplate
          ? raw
          : TemplateDisparity(left, stereo.right, mask, box, stereo.max_disparity, options_,
                              stereo.window);
  if (!estimate.valid()) return 0.0;
  auto it = jumps_.find(id);
  double jump = 0.0;
  if (it == jumps_.end()) {
    it = jumps_.emplace(id, JumpTrack(options_.jump_low_pass)).first;
  } else {
    // A move within three of the estimate's own standard deviations is not a jump: a flat or
    // repeating template's peak wanders by itself.
    jump = std::max(0.0, std::abs(estimate.disparity - it->second.last) - 3.0 * estimate.sd);
  }
  it->second.last = it->second.filter.Step(estimate.disparity);
  return jump;
}

DisparityEstimate TargetDepths::Last(int id) const {
  const auto it = tracks_.find(id);
  return it == tracks_.end() ? DisparityEstimate{} : it->second.last;
}

}  // namespace attend
