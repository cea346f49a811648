#include "tracker/correlation_target.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "tracker/hog_features.h"
#include "util/error.h"

namespace attend {
namespace tracker_internal {

namespace {

// The running means of the peak and sharpness are over about this many learnt frames (a plain
// mean before that many).
constexpr int kPeakMemory = 50;
// Frames that are always trusted after the start, while the mean peak settles.
constexpr int kSettleFrames = 3;
// The smallest target side the scale may shrink to, frame pixels, and the range of the scale
// against the first frame's: a target lost in blur or clutter otherwise lets the scale filter
// shrink it to a few pixels, from which it does not recover (OTB Dog1).
constexpr double kMinSide = 4.0;
constexpr double kMinScale = 0.2;
constexpr double kMaxScale = 5.0;

int WholeCells(double pixels, int cell, int min_cells) {
  return std::max(min_cells, static_cast<int>(std::lround(pixels / cell))) * cell;
}

// As WholeCells, the count of cells rounded up to a size the DFT is fast for.
int DftCells(double pixels, int cell, int min_cells) {
  const int cells = std::max(min_cells, static_cast<int>(std::lround(pixels / cell)));
  return cv::getOptimalDFTSize(cells) * cell;
}

// The part of `frame` of `size` centred at `centre`, bilinear at the exact position and size
// (the scale samples must differ by exactly their factors), resampled to `out`.
void ScalePatch(const cv::Mat& frame, const cv::Point2d& centre, const cv::Size2d& size,
                const cv::Size& out, cv::Mat* result) {
  const double sx = size.width / out.width, sy = size.height / out.height;
  const cv::Matx23d map(sx, 0, centre.x - size.width / 2 + 0.5 * sx - 0.5,  //
                        0, sy, centre.y - size.height / 2 + 0.5 * sy - 0.5);
  cv::warpAffine(frame, *result, map, out, cv::INTER_LINEAR | cv::WARP_INVERSE_MAP,
                 cv::BORDER_REPLICATE);
}

// The average peak-to-correlation energy (APCE; Wang, Liu and Huang, CVPR 2017, "Large
// margin object tracking with circulant feature maps"): (max - min)^2 over the mean of
// (value - min)^2. High for one sharp peak, low for a flat or many-peaked response.
double Sharpness(const cv::Mat& response, double max_value) {
  double min_value = 0.0;
  cv::minMaxLoc(response, &min_value);
  double sum = 0.0;
  for (int r = 0; r < response.rows; ++r) {
    const float* values = response.ptr<float>(r);
    for (int c = 0; c < response.cols; ++c) sum += (values[c] - min_value) * (values[c] - min_value);
  }
  const double mean = sum / static_cast<double>(response.total());
  return mean > 0.0 ? (max_value - min_value) * (max_value - min_value) / mean : 0.0;
}

// The part of `frame` of `size` (frame pixels) centred at `centre` (continuous coordinates:
// pixel i spans [i, i + 1)), border pixels repeated outside the frame, resampled to `out`
// into `result` (reused when it has that size). Bilinear at the exact position and size; a
// patch shrunk by more than kAreaShrink is averaged over whole frame pixels instead (INTER_AREA,
// no aliasing), its position rounded: the centre it has is returned either way.
constexpr double kAreaShrink = 1.5;

cv::Point2d SamplePatch(const cv::Mat& frame, const cv::Point2d& centre, const cv::Size2d& size,
                        const cv::Size& out, cv::Mat* border, cv::Mat* result) {
  const double sx = size.width / out.width, sy = size.height / out.height;
  if (sx <= kAreaShrink || sy <= kAreaShrink) {
    ScalePatch(frame, centre, size, out, result);
    return centre;
  }
  const int w = std::max(1, static_cast<int>(std::lround(size.width)));
  const int h = std::max(1, static_cast<int>(std::lround(size.height)));
  const int x0 = static_cast<int>(std::lround(centre.x - w / 2.0));
  const int y0 = static_cast<int>(std::lround(centre.y - h / 2.0));
  const cv::Rect wanted(x0, y0, w, h);
  const cv::Rect inside = wanted & cv::Rect(0, 0, frame.cols, frame.rows);
  cv::Mat region;
  if (inside == wanted) {
    region = frame(wanted);
  } else if (inside.empty()) {
    // Wholly outside: the nearest frame pixel, repeated.
    const int cx = std::clamp(x0 + w / 2, 0, frame.cols - 1);
    const int cy = std::clamp(y0 + h / 2, 0, frame.rows - 1);
    cv::copyMakeBorder(frame(cv::Rect(cx, cy, 1, 1)), *border, 0, h - 1, 0, w - 1,
                       cv::BORDER_REPLICATE);
    region = *border;
  } else {
    cv::copyMakeBorder(frame(inside), *border, inside.y - y0, wanted.br().y - inside.br().y,
                       inside.x - x0, wanted.br().x - inside.br().x, cv::BORDER_REPLICATE);
    region = *border;
  }
  cv::resize(region, *result, out, 0, 0, cv::INTER_AREA);
  return {x0 + w / 2.0, y0 + h / 2.0};
}

// Column n of the result is column n + shift of `samples`, clamped to its columns.
cv::Mat ShiftColumns(const cv::Mat& samples, int shift) {
  if (shift == 0) return samples;
  cv::Mat shifted(samples.size(), samples.type());
  for (int n = 0; n < samples.cols; ++n) {
    samples.col(std::clamp(n + shift, 0, samples.cols - 1)).copyTo(shifted.col(n));
  }
  return shifted;
}

}  // namespace

CorrelationTarget::CorrelationTarget(const CorrelationOptions& options, const cv::Mat& frame,
                                     const cv::Rect& box)
    : options_(options),
      base_size_(std::max(1, box.width), std::max(1, box.height)),
      window_base_(base_size_.width + options.padding * 0.5 * (base_size_.width + base_size_.height),
                   base_size_.height + options.padding * 0.5 * (base_size_.width + base_size_.height)),
      model_window_([&] {
        const double f = std::sqrt(options.window_area / window_base_.area());
        return cv::Size(DftCells(window_base_.width * f, options.cell, 4),
                        DftCells(window_base_.height * f, options.cell, 4));
      }()),
      model_factor_(model_window_.width / window_base_.width,
                    model_window_.height / window_base_.height),
      target_model_(std::max(1, static_cast<int>(std::lround(base_size_.width * model_factor_.x))),
                    std::max(1, static_cast<int>(std::lround(base_size_.height * model_factor_.y)))),
      scale_model_([&] {
        const double f = std::sqrt(options.scale_area / base_size_.area());
        return cv::Size(WholeCells(base_size_.width * f, options.cell, 2),
                        WholeCells(base_size_.height * f, options.cell, 2));
      }()),
      filter_(cv::Size(model_window_.width / options.cell, model_window_.height / options.cell),
              std::max(0.5, options.label_sigma *
                                std::sqrt(base_size_.area() * model_factor_.x * model_factor_.y) /
                                options.cell),
              options.filter_lambda),
      scale_filter_(options.scales, std::sqrt(static_cast<double>(options.scales)) / 4.0, 1e-2),
      colour_(options.colour_bins),
      centre_(box.x + 0.5 * box.width, box.y + 0.5 * box.height) {
  ATTEND_CHECK(frame.type() == CV_8UC3 && !box.empty()) << "a target needs a BGR frame and a box";
  for (int n = 0; n < options.scales; ++n) {
    scale_factors_.push_back(std::pow(options.scale_step, n - options.scales / 2));
  }
  min_scale_ = std::min(1.0, std::max(kMinScale, kMinSide / std::min(base_size_.width, base_size_.height)));
  max_scale_ = std::max(1.0, std::min({kMaxScale, frame.cols / base_size_.width,
                                       frame.rows / base_size_.height}));
  Learn(frame, options.scales > 1 ? ScaleSamples(frame, centre_) : cv::Mat(), 1.0, 1.0, 1.0);
  UpdateBox(frame.size());
}

const cv::Mat& CorrelationTarget::Window(const cv::Mat& frame, const cv::Point2d& centre,
                                         cv::Point2d* actual) {
  const cv::Point2d at = SamplePatch(frame, centre, window_base_ * scale_, model_window_, &border_,
                                     &patch_);
  if (actual != nullptr) *actual = at;
  return patch_;
}

CorrelationTarget::Search CorrelationTarget::SearchAt(const cv::Mat& frame,
                                                      const cv::Point2d& centre) {
  cv::Point2d at;
  const cv::Mat& patch = Window(frame, centre, &at);
  hog_.Compute(patch, options_.cell, &channels_);
  cv::Mat response = filter_.Respond(channels_);
  if (options_.colour_share > 0.f && colour_.trained()) {
    colour_.Likelihood(patch, &likelihood_);
    const cv::Mat colour =
        ColourResponse(likelihood_, filter_.cells(), options_.cell, target_model_);
    cv::addWeighted(response, 1.0 - options_.colour_share, colour, options_.colour_share, 0.0,
                    response);
  }
  Search search;
  const cv::Point2d peak = ResponsePeak(response, &search.peak);
  search.sharpness = Sharpness(response, search.peak);
  // Cells of the model window to frame pixels at the current scale.
  search.offset = cv::Point2d(peak.x - response.cols / 2, peak.y - response.rows / 2);
  search.centre = at + cv::Point2d(
                                (peak.x - response.cols / 2) * options_.cell / model_factor_.x * scale_,
                                (peak.y - response.rows / 2) * options_.cell / model_factor_.y * scale_);
  return search;
}

CorrelationTarget::Search CorrelationTarget::SearchWider(const cv::Mat& frame,
                                                         const cv::Point2d& centre) {
  Search best;
  const cv::Size2d half = window_base_ * (0.5 * scale_);
  const int k = options_.redetect_windows;
  for (int j = -k; j <= k; ++j) {
    for (int i = -k; i <= k; ++i) {
      if (i == 0 && j == 0) continue;
      const cv::Point2d at(centre.x + i * half.width, centre.y + j * half.height);
      if (at.x < 0 || at.y < 0 || at.x > frame.cols || at.y > frame.rows) continue;
      const Search search = SearchAt(frame, at);
      if (search.peak > best.peak) best = search;
    }
  }
  return best;
}

cv::Mat CorrelationTarget::ScaleSamples(const cv::Mat& frame, const cv::Point2d& centre) {
  cv::Mat samples;
  std::vector<cv::Mat>& channels = channels_;
  for (size_t n = 0; n < scale_factors_.size(); ++n) {
    ScalePatch(frame, centre, base_size_ * (scale_ * scale_factors_[n]), scale_model_,
               &scale_patch_);
    hog_.Compute(scale_patch_, options_.cell, &channels);
    if (samples.empty()) {
      samples.create(static_cast<int>(channels.size() * channels[0].total()),
                     static_cast<int>(scale_factors_.size()), CV_32F);
    }
    int row = 0;
    for (const cv::Mat& channel : channels) {
      for (int r = 0; r < channel.rows; ++r) {
        const float* values = channel.ptr<float>(r);
        for (int c = 0; c < channel.cols; ++c) samples.at<float>(row++, static_cast<int>(n)) = values[c];
      }
    }
  }
  return samples;
}

void CorrelationTarget::Learn(const cv::Mat& frame, const cv::Mat& scale_samples,
                              double filter_rate, double colour_rate, double scale_rate) {
  const cv::Mat& patch = Window(frame, centre_);
  hog_.Compute(patch, options_.cell, &channels_);
  filter_.Learn(channels_, filter_rate);
  LearnColour(patch, cv::Point2d(), colour_rate);
  if (!scale_samples.empty()) scale_filter_.Learn(scale_samples, scale_rate);
}

void CorrelationTarget::LearnColour(const cv::Mat& patch, const cv::Point2d& offset, double rate) {
  if (options_.colour_share <= 0.f) return;
  const cv::Size2d target(base_size_.width * model_factor_.x, base_size_.height * model_factor_.y);
  const cv::Point2d middle(model_window_.width / 2.0 + offset.x, model_window_.height / 2.0 + offset.y);
  const cv::Rect target_box(cv::Point(static_cast<int>(std::lround(middle.x - target.width / 2)),
                                      static_cast<int>(std::lround(middle.y - target.height / 2))),
                            cv::Size(static_cast<int>(std::lround(target.width)),
                                     static_cast<int>(std::lround(target.height))));
  const int shrink = static_cast<int>(
      std::lround(options_.inner_padding * 0.5 * (target.width + target.height) / 2.0));
  cv::Rect inner = target_box;
  if (inner.width > 2 * shrink && inner.height > 2 * shrink) {
    inner = cv::Rect(inner.x + shrink, inner.y + shrink, inner.width - 2 * shrink,
                     inner.height - 2 * shrink);
  }
  colour_.Learn(patch, inner, target_box, rate);
}

void CorrelationTarget::LearnFromSearch(const cv::Point2d& offset, const cv::Mat& scale_samples) {
  filter_.LearnLastResponded(offset, options_.filter_rate);
  LearnColour(patch_, offset * options_.cell, options_.colour_rate);
  if (!scale_samples.empty()) scale_filter_.Learn(scale_samples, options_.scale_rate);
}

void CorrelationTarget::UpdateBox(cv::Size frame_size) {
  const cv::Size2d size = base_size_ * scale_;
  const int x0 = static_cast<int>(std::lround(centre_.x - size.width / 2));
  const int y0 = static_cast<int>(std::lround(centre_.y - size.height / 2));
  const int x1 = static_cast<int>(std::lround(centre_.x + size.width / 2));
  const int y1 = static_cast<int>(std::lround(centre_.y + size.height / 2));
  cv::Rect box = cv::Rect(x0, y0, std::max(1, x1 - x0), std::max(1, y1 - y0)) &
                 cv::Rect(0, 0, frame_size.width, frame_size.height);
  if (!box.empty()) box_ = box;
}

TrackState CorrelationTarget::Track(const cv::Mat& frame) {
  ATTEND_CHECK(frame.type() == CV_8UC3) << "frames must be 8-bit BGR";
  const cv::Point2d predicted = centre_ + velocity_ * options_.motion;
  Search search = SearchAt(frame, predicted);
  const bool settling = learnt_frames_ < kSettleFrames;
  auto trusted = [&](double peak) {
    return settling || options_.confidence_ratio <= 0.f ||
           peak >= options_.confidence_ratio * mean_peak_;
  };
  // A weak peak (under search_ratio of the usual, or untrusted) is searched for over the
  // wider window too; the best peak wins.
  const bool weak = !trusted(search.peak) ||
                    (!settling && search.peak < options_.search_ratio * mean_peak_);
  // The window and features of the search that won, for learning (reuse_search); a wider
  // search overwrites them.
  bool search_kept = true;
  if (weak && options_.redetect_windows > 0) {
    const Search wider = SearchWider(frame, predicted);
    search_kept = false;
    if (wider.peak > search.peak) search = wider;
  }
  peak_ = search.peak;
  if (!trusted(search.peak)) {
    velocity_ = cv::Point2d();
    ++missed_;
    return missed_ >= options_.missed_frames ? TrackState::kLost : TrackState::kOccluded;
  }
  missed_ = 0;
  velocity_ = search.centre - centre_;
  centre_ = search.centre;
  centre_.x = std::clamp(centre_.x, 0.0, static_cast<double>(frame.cols));
  centre_.y = std::clamp(centre_.y, 0.0, static_cast<double>(frame.rows));
  cv::Mat samples;
  bool learn_last_samples = false;
  ++frames_;
  if (options_.scales > 1 && frames_ % options_.scale_every == 0) {
    samples = ScaleSamples(frame, centre_);
    const double best = scale_filter_.BestSample(samples);
    scale_ *= std::pow(options_.scale_step, best - options_.scales / 2);
    scale_ = std::clamp(scale_, min_scale_, max_scale_);
    // The samples, taken at the old scale, are learnt as if taken at the new one: their
    // columns shift by the whole steps of the change, the edge columns repeated.
    const int shift = static_cast<int>(std::lround(best)) - options_.scales / 2;
    // Unshifted (most frames), the filter learns from the spectra it has just computed.
    samples = shift == 0 ? cv::Mat() : ShiftColumns(samples, shift);
    learn_last_samples = shift == 0;
  }
  UpdateBox(frame.size());
  // Found, but learnt from only when its response is as high and as sharp as usual.
  const bool learn = settling || (search.peak >= options_.learn_ratio * mean_peak_ &&
                                  search.sharpness >= options_.learn_sharpness * mean_sharpness_);
  if (learn) {
    ++learnt_frames_;
    const int memory = std::min(learnt_frames_, kPeakMemory);
    mean_peak_ += (search.peak - mean_peak_) / memory;
    mean_sharpness_ += (search.sharpness - mean_sharpness_) / memory;
    if (learn_last_samples) scale_filter_.LearnLastSamples(options_.scale_rate);
    if (options_.reuse_search && search_kept) {
      LearnFromSearch(search.offset, samples);
    } else {
      Learn(frame, samples, options_.filter_rate, options_.colour_rate, options_.scale_rate);
    }
  }
  return TrackState::kFound;
}

}  // namespace tracker_internal
}  // namespace attend
