#include "features/centre_surround.h"

#include "config/read_fields.h"

#include <opencv2/imgproc.hpp>

namespace attend {

namespace {

class CentreSurroundFeature final : public FeatureMap {
 public:
  bool ReadsAttentionRegions() const override { return false; }
  explicit CentreSurroundFeature(const CentreSurroundOptions& options) : options_(options) {}
  void Compute(const FrameContext& context, cv::Mat* out) override {
    CentreSurroundMap(context.left(), options_, out);
  }

 private:
  CentreSurroundOptions options_;
};

void MinMaxInPlace(cv::Mat* map) {
  double low = 0.0, high = 0.0;
  cv::minMaxLoc(*map, &low, &high);
  if (high > low) {
    *map = (*map - low) / (high - low);
  } else {
    map->setTo(0.f);
  }
}

}  // namespace

const OptionFields<CentreSurroundOptions>& CentreSurroundOptions::Fields() {
  using O = CentreSurroundOptions;
  static const OptionFields<CentreSurroundOptions> fields = {
      {"scales", &O::scales, ScaleRange(), "the centre sigmas, px at the working size"},
      {"surround", &O::surround, Range::AboveUpTo(1, 50), "surround sigma over centre sigma"}};
  return fields;
}

std::string CentreSurroundOptions::Check() const {
  if (scales.empty()) return "scales must not be empty";
  for (const double c : scales) {
    if (!ScaleRange().Contains(c)) return "scales: each " + ScaleRange().Describe();
  }
  return CheckFieldRanges(*this, Fields());
}

void CentreSurroundMap(const cv::Mat& bgr, const CentreSurroundOptions& options, cv::Mat* out) {
  CV_Assert(bgr.type() == CV_8UC3 && !bgr.empty());
  cv::Mat unit, lab;
  bgr.convertTo(unit, CV_32F, 1.0 / 255.0);
  cv::cvtColor(unit, lab, cv::COLOR_BGR2Lab);
  // L in [0, 100], a and b in about [-127, 127]: to comparable [0, 1]-sized units.
  lab = lab.mul(cv::Scalar(1.0 / 100.0, 1.0 / 255.0, 1.0 / 255.0));
  out->create(bgr.size(), CV_32FC1);
  out->setTo(0.f);
  cv::Mat centre, surround, difference, distance;
  for (const double c : options.scales) {
    cv::GaussianBlur(lab, centre, cv::Size(), c, c, cv::BORDER_REPLICATE);
    const double s = c * options.surround;
    cv::GaussianBlur(lab, surround, cv::Size(), s, s, cv::BORDER_REPLICATE);
    cv::subtract(centre, surround, difference);
    difference = difference.mul(difference);
    cv::transform(difference, distance, cv::Matx13f(1.f, 1.f, 1.f));
    cv::sqrt(distance, distance);
    MinMaxInPlace(&distance);
    *out += distance;
  }
  *out /= static_cast<double>(options.scales.size());
}

std::unique_ptr<FeatureMap> CreateCentreSurroundFeature(const ParamBlock& params,
                                                        const FeatureSetup&) {
  CentreSurroundOptions options;
  ReadFields(params, CentreSurroundOptions::Fields(), &options);
  const std::string error = options.Check();
  if (!error.empty()) params.FailCheck(error);
  return std::make_unique<CentreSurroundFeature>(options);
}

}  // namespace attend
