// The discriminative correlation filters of the correlation tracker (tracker/correlation_tracker.h),
// learnt in the Fourier domain as in Danelljan et al.'s DSST (BMVC 2014, "Accurate scale
// estimation for robust visual tracking"): for feature channels f_l and a Gaussian desired
// response g, the filter's numerator is A_l = conj(G) F_l and its denominator
// B = sum_l conj(F_l) F_l, each a running average over the frames (rate eta); the response to
// features z is y = IDFT(sum_l conj(A_l) Z_l / (B + lambda)). Not part of the API.
#pragma once

#include <opencv2/core.hpp>
#include <vector>

namespace attend {
namespace tracker_internal {

// Translation: a 2-D filter over cells of features, cosine-windowed. The desired response
// peaks at the window's centre; Respond returns its response with the same layout, so the
// peak's offset from (cols / 2, rows / 2) is the target's displacement in cells.
class TranslationFilter {
 public:
  // A filter over `cells` (columns x rows) whose desired response is a Gaussian of
  // `sigma_cells`; `lambda` regularises the denominator.
  TranslationFilter(cv::Size cells, double sigma_cells, double lambda);

  // Blends the filter learnt from `channels` (CV_32FC1 maps of the cells' size) in by `rate`
  // (1: replaces it).
  void Learn(const std::vector<cv::Mat>& channels, double rate);
  // Blends in, by `rate`, the filter learnt from the features of the last Respond call with its
  // desired response's peak moved by `shift` cells from the centre (where the target was found
  // in them): the search's features teach the filter without being extracted again.
  void LearnLastResponded(const cv::Point2d& shift, double rate);
  // The response to `channels` (CV_32FC1, the cells' size), centred.
  cv::Mat Respond(const std::vector<cv::Mat>& channels);

  cv::Size cells() const { return cells_; }
  bool trained() const { return !denominator_.empty(); }

 private:
  // The windowed spectra of `channels`, into spectra_.
  void Spectra(const std::vector<cv::Mat>& channels);
  // Blends in the filter learnt from spectra_ against the desired response `label` (spectrum).
  void LearnSpectra(const cv::Mat& label, double rate);

  cv::Size cells_;
  double lambda_;
  cv::Mat window_;                   // CV_32F Hann window over the cells
  cv::Mat label_;                    // CV_32FC2: the desired response's spectrum
  std::vector<cv::Mat> numerator_;   // CV_32FC2 per channel
  cv::Mat denominator_;              // CV_32F
  // Buffers kept between calls.
  cv::Mat windowed_, product_, sum_;
  std::vector<cv::Mat> spectra_;
};

// Scale: a 1-D filter over `scales` samples of the target at scale factors step^(n - (S-1)/2),
// each sample a column of features, Hann-windowed across the samples. The desired response
// peaks at the middle sample.
class ScaleFilter {
 public:
  ScaleFilter(int scales, double sigma_samples, double lambda);

  // `samples`: CV_32F, one row per feature, one column per scale sample.
  void Learn(const cv::Mat& samples, double rate);
  // As Learn, from the samples of the last BestSample call (their spectra are kept).
  void LearnLastSamples(double rate);
  // The index of the sample that responds most, refined by a parabola through its neighbours
  // (a fractional index); its response in `peak`.
  double BestSample(const cv::Mat& samples, double* peak = nullptr);

  int scales() const { return scales_; }
  bool trained() const { return !denominator_.empty(); }

 private:
  // The windowed spectra of `samples`' rows, into spectra_.
  void Spectra(const cv::Mat& samples);

  int scales_;
  double lambda_;
  cv::Mat window_;       // 1 x S
  cv::Mat label_;        // 1 x S, CV_32FC2
  cv::Mat numerator_;    // D x S, CV_32FC2
  cv::Mat denominator_;  // 1 x S, CV_32F
  // Buffers kept between calls.
  cv::Mat windowed_, spectra_;
};

// The position of the largest value of a response map, refined along each axis by a parabola
// through it and its two neighbours (sub-cell), and that value.
cv::Point2d ResponsePeak(const cv::Mat& response, double* value);

}  // namespace tracker_internal
}  // namespace attend
