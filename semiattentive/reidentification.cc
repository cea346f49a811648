#include "semiattentive/reidentification.h"

#include <algorithm>
#include <opencv2/imgproc.hpp>

#include "util/error.h"
#include "util/opencv_extra.h"

namespace attend {

namespace {

// ImageNet's per-channel statistics, RGB, on [0, 1].
const cv::Scalar kMean(0.485, 0.456, 0.406);
const cv::Scalar kDeviation(0.229, 0.224, 0.225);

}  // namespace

const OptionFields<AppearanceOptions>& AppearanceOptions::Fields() {
  using O = AppearanceOptions;
  static const OptionFields<AppearanceOptions> fields = {
      {"appearance", &O::model,
       "a re-identification network (OSNet, docs/MODELS.md) for what targets look like; "
       "empty: colour histogram and grey template"},
      {"appearance_width", &O::width, Range::Closed(8, 1024), "the network's input width, px"},
      {"appearance_height", &O::height, Range::Closed(8, 1024), "the network's input height, px"},
      {"appearance_every", &O::every, Range::Closed(1, 1000),
       "a followed target's embedding is taken every this many frames it is kept"}};
  return fields;
}

std::string AppearanceOptions::Check() const { return CheckFieldRanges(*this, Fields()); }

std::unique_ptr<Reidentifier> Reidentifier::Load(const AppearanceOptions& options,
                                                 const std::string& where) {
  std::unique_ptr<cvextra::DnnNet> net;
  try {
    net = cvextra::Get("attention.appearance (OpenCV's dnn)").ReadNet(options.model, "");
  } catch (const cv::Exception& e) {
    throw InputError(where + ": " + options.model + ": cv::dnn cannot read it: " + e.err);
  }
  std::unique_ptr<Reidentifier> reidentifier(new Reidentifier(options, std::move(net)));
  cv::Mat probe;
  try {
    probe = reidentifier->Forward(
        cv::Mat(options.height, options.width, CV_8UC3, cv::Scalar::all(128)));
  } catch (const cv::Exception& e) {
    throw InputError(where + ": " + options.model + ": cv::dnn cannot run it on a " +
                     std::to_string(options.width) + "x" + std::to_string(options.height) +
                     " crop: " + e.err);
  }
  if (probe.empty()) {
    throw InputError(where + ": " + options.model +
                     ": not a re-identification network: it gives no single vector for a crop");
  }
  reidentifier->dimensions_ = probe.cols;
  return reidentifier;
}

Reidentifier::Reidentifier(const AppearanceOptions& options, std::unique_ptr<cvextra::DnnNet> net)
    : options_(options), net_(std::move(net)) {}

Reidentifier::~Reidentifier() = default;

cv::Mat Reidentifier::Forward(const cv::Mat& crop) {
  cv::resize(crop, resized_, cv::Size(options_.width, options_.height), 0, 0, cv::INTER_LINEAR);
  cv::cvtColor(resized_, rgb_, cv::COLOR_BGR2RGB);
  rgb_.convertTo(normalised_, CV_32FC3, 1.0 / 255.0);
  cv::subtract(normalised_, kMean, normalised_);
  cv::divide(normalised_, kDeviation, normalised_);
  net_->Forward(normalised_, 1.0, cv::Scalar(), false, &outputs_);
  // One output of one vector (1 x D, or 1 x D x 1 x 1).
  if (outputs_.size() != 1 || outputs_[0].depth() != CV_32F || outputs_[0].total() < 2 ||
      outputs_[0].size[0] != 1) {
    return cv::Mat();
  }
  cv::Mat embedding = outputs_[0].reshape(1, 1).clone();
  const double norm = cv::norm(embedding);
  if (norm > 1e-12) embedding /= norm;
  return embedding;
}

cv::Mat Reidentifier::Embed(const cv::Mat& bgr, const cv::Rect& box) {
  const cv::Rect inside = box & cv::Rect(0, 0, bgr.cols, bgr.rows);
  if (inside.width < 2 || inside.height < 2) return cv::Mat();
  return Forward(bgr(inside));
}

double EmbeddingSimilarity(const cv::Mat& a, const cv::Mat& b) {
  if (a.empty() || b.empty() || a.total() != b.total()) return 0.0;
  return std::max(0.0, a.dot(b));
}

}  // namespace attend
