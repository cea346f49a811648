#include "features/motion.h"

#include "config/read_fields.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "features/skin.h"

namespace attend {

namespace {

// The median of `values` (reordered).
float Median(std::vector<float>* values) {
  CV_Assert(!values->empty());
  auto middle = values->begin() + values->size() / 2;
  std::nth_element(values->begin(), middle, values->end());
  return *middle;
}

// Every `stride`-th pixel of every `stride`-th row: the statistics of a frame from a regular
// sample, so that they do not depend on anything but the image.
void Sample(const cv::Mat& image, int stride, std::vector<float>* out) {
  out->clear();
  for (int y = stride / 2; y < image.rows; y += stride) {
    const float* row = image.ptr<float>(y);
    for (int x = stride / 2; x < image.cols; x += stride) out->push_back(row[x]);
  }
  if (out->empty()) out->push_back(image.at<float>(0, 0));
}

// The frame-wide part of a frame's change from its background, L = g B + o, and its noise.
struct LightChange {
  double gain = 1.0, offset = 0.0;
  double noise = 0.0;  // the robust spread of the residual r = L - g B - o
};

// The light's change (the light, the camera's exposure) between the samples `background` and
// `luminance` (Sample, same pixels): fitted by least squares, then again on the samples the
// first fit explains (most of a frame does not move; what moves would bias the fit). `scratch`
// is a buffer kept between frames.
LightChange FitLightChange(const std::vector<float>& background,
                           const std::vector<float>& luminance, const MotionOptions& options,
                           std::vector<float>* scratch) {
  std::vector<uint8_t> inlier(background.size(), 1);
  double gain = 1.0, offset = 0.0, noise = 0.0;
  std::vector<float>& sample = *scratch;
  for (int pass = 0; pass < 2; ++pass) {
    double n = 0, sb = 0, sl = 0, sbb = 0, sbl = 0;
    for (size_t i = 0; i < inlier.size(); ++i) {
      if (!inlier[i]) continue;
      const double b = background[i], l = luminance[i];
      n += 1, sb += b, sl += l, sbb += b * b, sbl += b * l;
    }
    if (n >= 2) {
      const double variance = sbb - sb * sb / n;
      gain = variance > 1e-6 * n ? (sbl - sb * sl / n) / variance : 1.0;
      offset = (sl - gain * sb) / n;
    }
    // The residual's median (left-over offset) and robust spread (the sensor noise).
    sample.resize(inlier.size());
    for (size_t i = 0; i < inlier.size(); ++i) {
      sample[i] = static_cast<float>(luminance[i] - gain * background[i] - offset);
    }
    std::vector<float> residuals = sample;
    const float median = Median(&sample);
    offset += median;
    for (float& v : residuals) v -= median;
    sample = residuals;
    for (float& v : sample) v = std::abs(v);
    noise = 1.4826 * Median(&sample);
    const double bound = std::max(options.min_change, options.noise_factor * noise);
    for (size_t i = 0; i < inlier.size(); ++i) inlier[i] = std::abs(residuals[i]) <= bound;
  }
  return {gain, offset, noise};
}

class MotionFeature final : public FeatureMap {
 public:
  bool ReadsAttentionRegions() const override { return false; }
  explicit MotionFeature(const MotionOptions& options)
      : detector_(options), per_region_(options.per_region) {}
  void Compute(const FrameContext& context, cv::Mat* out) override {
    detector_.Compute(context.frame_index(), context.left(),
                      per_region_ ? &context.Regions() : nullptr, out);
  }

 private:
  MotionDetector detector_;
  bool per_region_;
};

}  // namespace

const OptionFields<MotionOptions>& MotionOptions::Fields() {
  using O = MotionOptions;
  static const OptionFields<MotionOptions> fields = {
      {"blur", &O::blur, Range::Closed(0, 50), "sigma of the Gaussian on the luminance, px"},
      {"rate", &O::rate, Range::AboveUpTo(0, 1),
       "background update rate; 1: the previous frame"},
      {"min_change", &O::min_change, Range::Closed(0, 255),
       "luminance change always treated as noise, grey levels"},
      {"noise_factor", &O::noise_factor, Range::Closed(0, 100),
       "change below this many robust noise sigmas is noise"},
      {"window", &O::window, Range::Closed(1, 201),
       "side of the box filter on the change, odd, px; 1: none"},
      {"per_region", &O::per_region, "average the change over each colour region"}};
  return fields;
}

std::string MotionOptions::Check() const {
  const std::string error = CheckFieldRanges(*this, Fields());
  if (!error.empty()) return error;
  if (window % 2 == 0) return "window must be odd";
  return "";
}

MotionDetector::MotionDetector(const MotionOptions& options) : options_(options) {
  const std::string error = options_.Check();
  CV_Assert(error.empty());
}

void MotionDetector::Compute(int frame_index, const cv::Mat& bgr,
                             const Segmentation* segmentation, cv::Mat* out) {
  CV_Assert(bgr.type() == CV_8UC3 && !bgr.empty());
  CV_Assert(!options_.per_region || segmentation != nullptr);
  cv::cvtColor(bgr, grey_, cv::COLOR_BGR2GRAY);
  grey_.convertTo(luminance_, CV_32F);
  if (options_.blur > 0.0) {
    cv::GaussianBlur(luminance_, luminance_, cv::Size(), options_.blur, options_.blur,
                     cv::BORDER_REPLICATE);
  }
  const bool restart = frame_index <= previous_index_ || background_.size() != luminance_.size();
  previous_index_ = frame_index;
  if (restart) {
    luminance_.copyTo(background_);
    out->create(bgr.size(), CV_32FC1);
    out->setTo(0.f);
    last_noise_ = 0.0;
    last_gain_ = 1.0;
    last_offset_ = 0.0;
    return;
  }

  constexpr int kStride = 3;
  Sample(background_, kStride, &background_sample_);
  Sample(luminance_, kStride, &luminance_sample_);
  const LightChange light =
      FitLightChange(background_sample_, luminance_sample_, options_, &sample_);
  last_gain_ = light.gain;
  last_offset_ = light.offset;
  last_noise_ = light.noise;
  const double floor = std::max(options_.min_change, options_.noise_factor * light.noise);
  // r = L - g B - o
  cv::scaleAdd(background_, -light.gain, luminance_, residual_);
  residual_ -= light.offset;
  scratch_ = cv::abs(residual_);
  scratch_ -= floor;
  cv::max(scratch_, 0.0, scratch_);
  if (options_.per_region) {
    scratch_.copyTo(*out);
    AverageOverRegions(*segmentation, out);
  } else if (options_.window > 1) {
    cv::boxFilter(scratch_, *out, CV_32F, cv::Size(options_.window, options_.window),
                  cv::Point(-1, -1), true, cv::BORDER_REPLICATE);
  } else {
    scratch_.copyTo(*out);
  }

  // The background follows the frame (eq. above; rate 1 keeps just the previous frame).
  if (options_.rate >= 1.0) {
    luminance_.copyTo(background_);
  } else {
    cv::addWeighted(background_, 1.0 - options_.rate, luminance_, options_.rate, 0.0,
                    background_);
  }
}

std::unique_ptr<FeatureMap> CreateMotionFeature(const ParamBlock& params, const FeatureSetup&) {
  MotionOptions options;
  ReadFields(params, MotionOptions::Fields(), &options);
  const std::string error = options.Check();
  if (!error.empty()) params.FailCheck(error);
  return std::make_unique<MotionFeature>(options);
}

}  // namespace attend
