#include "tracker/correlation_filter.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "util/error.h"

namespace attend {
namespace tracker_internal {

namespace {

// Adds `weight` times the squared magnitude of a CV_32FC2 spectrum to `sum` (CV_32F).
void AddPower(const cv::Mat& spectrum, float weight, cv::Mat* sum) {
  for (int r = 0; r < spectrum.rows; ++r) {
    const cv::Vec2f* f = spectrum.ptr<cv::Vec2f>(r);
    float* out = sum->ptr<float>(r);
    for (int c = 0; c < spectrum.cols; ++c) out[c] += weight * (f[c][0] * f[c][0] + f[c][1] * f[c][1]);
  }
}

// spectrum / (real + lambda), element by element.
cv::Mat DivideByReal(const cv::Mat& spectrum, const cv::Mat& real, double lambda) {
  cv::Mat planes[2];
  cv::split(spectrum, planes);
  const cv::Mat denominator = real + lambda;
  cv::divide(planes[0], denominator, planes[0]);
  cv::divide(planes[1], denominator, planes[1]);
  cv::Mat result;
  cv::merge(planes, 2, result);
  return result;
}

// A 1-D Hann window of n samples.
cv::Mat Hann(int n) {
  cv::Mat window(1, n, CV_32F);
  for (int i = 0; i < n; ++i) {
    window.at<float>(0, i) =
        n == 1 ? 1.f : static_cast<float>(0.5 * (1.0 - std::cos(2.0 * CV_PI * i / (n - 1))));
  }
  return window;
}

// Parabola through (-1, a), (0, b), (1, c): the offset of its vertex, in [-0.5, 0.5].
double ParabolaOffset(double a, double b, double c) {
  const double curvature = a - 2.0 * b + c;
  if (curvature >= 0.0) return 0.0;
  return std::clamp(0.5 * (a - c) / curvature, -0.5, 0.5);
}

}  // namespace

TranslationFilter::TranslationFilter(cv::Size cells, double sigma_cells, double lambda)
    : cells_(cells), lambda_(lambda) {
  ATTEND_CHECK(cells.width > 0 && cells.height > 0 && sigma_cells > 0.0)
      << "a translation filter needs cells and a positive sigma";
  window_ = Hann(cells.height).t() * Hann(cells.width);
  // The desired response, peaking at the cell (0, 0) with circular wrap-around: its spectrum
  // then needs no phase, and Respond shifts the peak back to the centre.
  cv::Mat label(cells, CV_32F);
  for (int r = 0; r < cells.height; ++r) {
    const int dr = r <= cells.height / 2 ? r : r - cells.height;
    for (int c = 0; c < cells.width; ++c) {
      const int dc = c <= cells.width / 2 ? c : c - cells.width;
      label.at<float>(r, c) = static_cast<float>(
          std::exp(-0.5 * (dr * dr + dc * dc) / (sigma_cells * sigma_cells)));
    }
  }
  cv::dft(label, label_, cv::DFT_COMPLEX_OUTPUT);
}

void TranslationFilter::Spectra(const std::vector<cv::Mat>& channels) {
  spectra_.resize(channels.size());
  for (size_t l = 0; l < channels.size(); ++l) {
    ATTEND_CHECK(channels[l].size() == cells_ && channels[l].type() == CV_32F)
        << "features must match the filter's cells";
    cv::multiply(channels[l], window_, windowed_);
    cv::dft(windowed_, spectra_[l], cv::DFT_COMPLEX_OUTPUT);
  }
}

void TranslationFilter::Learn(const std::vector<cv::Mat>& channels, double rate) {
  Spectra(channels);
  LearnSpectra(label_, rate);
}

void TranslationFilter::LearnLastResponded(const cv::Point2d& shift, double rate) {
  ATTEND_CHECK(trained() && !spectra_.empty()) << "learning from a response needs one";
  // The label moved by `shift`: its spectrum times exp(-2 pi i (u sx / W + v sy / H)), with
  // the frequencies u, v taken in (-W/2, W/2] so that a fraction of a cell moves it smoothly.
  cv::Mat shifted(label_.size(), CV_32FC2);
  for (int v = 0; v < cells_.height; ++v) {
    const double fv = (v <= cells_.height / 2 ? v : v - cells_.height) / static_cast<double>(cells_.height);
    const cv::Vec2f* g = label_.ptr<cv::Vec2f>(v);
    cv::Vec2f* out = shifted.ptr<cv::Vec2f>(v);
    for (int u = 0; u < cells_.width; ++u) {
      const double fu = (u <= cells_.width / 2 ? u : u - cells_.width) / static_cast<double>(cells_.width);
      const double angle = -2.0 * CV_PI * (fu * shift.x + fv * shift.y);
      const float c = static_cast<float>(std::cos(angle)), s = static_cast<float>(std::sin(angle));
      out[u] = cv::Vec2f(g[u][0] * c - g[u][1] * s, g[u][0] * s + g[u][1] * c);
    }
  }
  LearnSpectra(shifted, rate);
}

void TranslationFilter::LearnSpectra(const cv::Mat& label, double rate) {
  const bool replace = !trained() || rate >= 1.0 || numerator_.size() != spectra_.size();
  if (replace) {
    numerator_.resize(spectra_.size());
    denominator_ = cv::Mat::zeros(cells_, CV_32F);
  } else {
    denominator_ *= 1.0 - rate;
  }
  for (size_t l = 0; l < spectra_.size(); ++l) {
    cv::mulSpectrums(spectra_[l], label, product_, 0, true);  // F_l conj(G)
    if (replace) {
      product_.copyTo(numerator_[l]);
    } else {
      cv::addWeighted(numerator_[l], 1.0 - rate, product_, rate, 0.0, numerator_[l]);
    }
    AddPower(spectra_[l], replace ? 1.f : static_cast<float>(rate), &denominator_);
  }
}

cv::Mat TranslationFilter::Respond(const std::vector<cv::Mat>& channels) {
  ATTEND_CHECK(trained()) << "a translation filter responds only once learnt";
  Spectra(channels);
  sum_.create(cells_, CV_32FC2);
  sum_.setTo(cv::Scalar::all(0));
  for (size_t l = 0; l < spectra_.size(); ++l) {
    cv::mulSpectrums(spectra_[l], numerator_[l], product_, 0, true);  // Z_l conj(A_l)
    sum_ += product_;
  }
  cv::Mat response;
  cv::dft(DivideByReal(sum_, denominator_, lambda_), response,
          cv::DFT_INVERSE | cv::DFT_REAL_OUTPUT | cv::DFT_SCALE);
  // Shift the zero displacement from (0, 0) to the centre (cols / 2, rows / 2).
  cv::Mat centred(cells_, CV_32F);
  const int cx = cells_.width / 2, cy = cells_.height / 2;
  for (int r = 0; r < cells_.height; ++r) {
    const float* source = response.ptr<float>(r);
    float* target = centred.ptr<float>((r + cy) % cells_.height);
    for (int c = 0; c < cells_.width; ++c) target[(c + cx) % cells_.width] = source[c];
  }
  return centred;
}

ScaleFilter::ScaleFilter(int scales, double sigma_samples, double lambda)
    : scales_(scales), lambda_(lambda) {
  ATTEND_CHECK(scales > 0 && sigma_samples > 0.0) << "a scale filter needs samples and a sigma";
  window_ = Hann(scales);
  // Peaks at the middle sample (scale factor 1), so the response's peak is the best sample.
  cv::Mat label(1, scales, CV_32F);
  for (int n = 0; n < scales; ++n) {
    const double d = n - scales / 2;
    label.at<float>(0, n) = static_cast<float>(std::exp(-0.5 * d * d / (sigma_samples * sigma_samples)));
  }
  cv::dft(label, label_, cv::DFT_COMPLEX_OUTPUT | cv::DFT_ROWS);
}

void ScaleFilter::Spectra(const cv::Mat& samples) {
  ATTEND_CHECK(samples.type() == CV_32F && samples.cols == scales_)
      << "scale samples need one column per scale";
  windowed_.create(samples.size(), CV_32F);
  const float* window = window_.ptr<float>(0);
  for (int d = 0; d < samples.rows; ++d) {
    const float* in = samples.ptr<float>(d);
    float* out = windowed_.ptr<float>(d);
    for (int n = 0; n < scales_; ++n) out[n] = in[n] * window[n];
  }
  cv::dft(windowed_, spectra_, cv::DFT_COMPLEX_OUTPUT | cv::DFT_ROWS);
}

void ScaleFilter::Learn(const cv::Mat& samples, double rate) {
  Spectra(samples);
  LearnLastSamples(rate);
}

void ScaleFilter::LearnLastSamples(double rate) {
  ATTEND_CHECK(!spectra_.empty()) << "learning the last samples needs some";
  const bool replace = !trained() || rate >= 1.0 || numerator_.size() != spectra_.size();
  if (replace) {
    numerator_.create(spectra_.size(), CV_32FC2);
    denominator_ = cv::Mat::zeros(1, scales_, CV_32F);
  } else {
    denominator_ *= 1.0 - rate;
  }
  const float keep = replace ? 0.f : static_cast<float>(1.0 - rate);
  const float add = replace ? 1.f : static_cast<float>(rate);
  const cv::Vec2f* label = label_.ptr<cv::Vec2f>(0);
  float* denominator = denominator_.ptr<float>(0);
  for (int d = 0; d < spectra_.rows; ++d) {
    const cv::Vec2f* f = spectra_.ptr<cv::Vec2f>(d);
    cv::Vec2f* a = numerator_.ptr<cv::Vec2f>(d);
    for (int n = 0; n < scales_; ++n) {
      // F conj(G)
      const float re = f[n][0] * label[n][0] + f[n][1] * label[n][1];
      const float im = f[n][1] * label[n][0] - f[n][0] * label[n][1];
      // (A new numerator's memory is not initialised: it is written, not blended.)
      a[n][0] = replace ? re : keep * a[n][0] + add * re;
      a[n][1] = replace ? im : keep * a[n][1] + add * im;
      denominator[n] += add * (f[n][0] * f[n][0] + f[n][1] * f[n][1]);
    }
  }
}

double ScaleFilter::BestSample(const cv::Mat& samples, double* peak) {
  ATTEND_CHECK(trained()) << "a scale filter responds only once learnt";
  Spectra(samples);
  ATTEND_CHECK(spectra_.rows == numerator_.rows) << "scale samples changed their length";
  // sum over the rows of Z conj(A), divided by the denominator.
  cv::Mat sum = cv::Mat::zeros(1, scales_, CV_32FC2);
  cv::Vec2f* total = sum.ptr<cv::Vec2f>(0);
  for (int d = 0; d < spectra_.rows; ++d) {
    const cv::Vec2f* z = spectra_.ptr<cv::Vec2f>(d);
    const cv::Vec2f* a = numerator_.ptr<cv::Vec2f>(d);
    for (int n = 0; n < scales_; ++n) {
      total[n][0] += z[n][0] * a[n][0] + z[n][1] * a[n][1];
      total[n][1] += z[n][1] * a[n][0] - z[n][0] * a[n][1];
    }
  }
  cv::Mat response;
  cv::dft(DivideByReal(sum, denominator_, lambda_), response,
          cv::DFT_INVERSE | cv::DFT_REAL_OUTPUT | cv::DFT_SCALE | cv::DFT_ROWS);
  auto at = [&](int n) { return static_cast<double>(response.at<float>(0, n)); };
  int best = 0;
  for (int n = 1; n < scales_; ++n) {
    if (at(n) > at(best)) best = n;
  }
  if (peak != nullptr) *peak = at(best);
  if (best == 0 || best == scales_ - 1) return best;
  return best + ParabolaOffset(at(best - 1), at(best), at(best + 1));
}

cv::Point2d ResponsePeak(const cv::Mat& response, double* value) {
  cv::Point best;
  double max_value = 0.0;
  cv::minMaxLoc(response, nullptr, &max_value, nullptr, &best);
  if (value != nullptr) *value = max_value;
  cv::Point2d peak(best.x, best.y);
  const int rows = response.rows, cols = response.cols;
  if (best.x > 0 && best.x < cols - 1) {
    peak.x += ParabolaOffset(response.at<float>(best.y, best.x - 1), max_value,
                             response.at<float>(best.y, best.x + 1));
  }
  if (best.y > 0 && best.y < rows - 1) {
    peak.y += ParabolaOffset(response.at<float>(best.y - 1, best.x), max_value,
                             response.at<float>(best.y + 1, best.x));
  }
  return peak;
}

}  // namespace tracker_internal
}  // namespace attend
