#include "tracker/colour_likelihood.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "util/error.h"

namespace attend {
namespace tracker_internal {

namespace {

// Blends a histogram of `counts` (summing to `total`) into `histogram` by `rate`.
void Blend(const std::vector<float>& counts, double total, double rate, bool first,
           std::vector<float>* histogram) {
  if (total <= 0.0) return;
  const float keep = first ? 0.f : static_cast<float>(1.0 - rate);
  const float add = static_cast<float>((first ? 1.0 : rate) / total);
  for (size_t i = 0; i < counts.size(); ++i) (*histogram)[i] = keep * (*histogram)[i] + add * counts[i];
}

}  // namespace

ColourLikelihood::ColourLikelihood(int bins) {
  shift_ = 0;
  while ((256 >> (shift_ + 1)) >= bins) ++shift_;
  bins_ = 256 >> shift_;
  target_.assign(static_cast<size_t>(bins_) * bins_ * bins_, 0.f);
  surroundings_ = target_;
}

void ColourLikelihood::Learn(const cv::Mat& patch, const cv::Rect& inner, const cv::Rect& target,
                             double rate) {
  ATTEND_CHECK(patch.type() == CV_8UC3) << "the colour model needs 8-bit BGR";
  in_.assign(target_.size(), 0.f);
  out_.assign(target_.size(), 0.f);
  std::vector<float>& in = in_;
  std::vector<float>& out = out_;
  double in_total = 0.0, out_total = 0.0;
  const cv::Rect inside = inner & cv::Rect(0, 0, patch.cols, patch.rows);
  for (int r = 0; r < patch.rows; ++r) {
    const cv::Vec3b* row = patch.ptr<cv::Vec3b>(r);
    const bool in_rows = r >= inside.y && r < inside.br().y;
    const bool target_rows = r >= target.y && r < target.br().y;
    for (int c = 0; c < patch.cols; ++c) {
      const int bin = Bin(row[c]);
      if (in_rows && c >= inside.x && c < inside.br().x) {
        in[bin] += 1.f;
        in_total += 1.0;
      }
      if (!(target_rows && c >= target.x && c < target.br().x)) {
        out[bin] += 1.f;
        out_total += 1.0;
      }
    }
  }
  Blend(in, in_total, rate, !trained_, &target_);
  Blend(out, out_total, rate, !trained_, &surroundings_);
  trained_ = trained_ || (in_total > 0.0 && out_total > 0.0);
}

void ColourLikelihood::Likelihood(const cv::Mat& patch, cv::Mat* likelihood) const {
  ATTEND_CHECK(patch.type() == CV_8UC3) << "the colour model needs 8-bit BGR";
  likelihood->create(patch.size(), CV_32F);
  cv::Mat& result = *likelihood;
  for (int r = 0; r < patch.rows; ++r) {
    const cv::Vec3b* row = patch.ptr<cv::Vec3b>(r);
    float* out = result.ptr<float>(r);
    for (int c = 0; c < patch.cols; ++c) {
      const int bin = Bin(row[c]);
      const float f = target_[bin], b = surroundings_[bin];
      out[c] = f + b > 0.f ? f / (f + b) : 0.f;
    }
  }
}

cv::Mat ColourResponse(const cv::Mat& likelihood, cv::Size cells, int cell, cv::Size target) {
  cv::Mat sums;
  cv::integral(likelihood, sums, CV_64F);
  const int w = std::max(1, target.width), h = std::max(1, target.height);
  const double area = static_cast<double>(w) * h;
  cv::Mat response(cells, CV_32F);
  for (int j = 0; j < cells.height; ++j) {
    const int y0 = std::clamp(j * cell - h / 2, 0, likelihood.rows);
    const int y1 = std::clamp(j * cell - h / 2 + h, 0, likelihood.rows);
    const double* top = sums.ptr<double>(y0);
    const double* bottom = sums.ptr<double>(y1);
    float* out = response.ptr<float>(j);
    for (int i = 0; i < cells.width; ++i) {
      const int x0 = std::clamp(i * cell - w / 2, 0, likelihood.cols);
      const int x1 = std::clamp(i * cell - w / 2 + w, 0, likelihood.cols);
      out[i] = static_cast<float>((bottom[x1] - bottom[x0] - top[x1] + top[x0]) / area);
    }
  }
  return response;
}

}  // namespace tracker_internal
}  // namespace attend
