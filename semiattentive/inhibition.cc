#include "semiattentive/inhibition.h"

#include <opencv2/imgproc.hpp>

#include "util/shared_mat.h"

namespace attend {

const OptionFields<InhibitionOptions>& InhibitionOptions::Fields() {
  using O = InhibitionOptions;
  static const OptionFields<InhibitionOptions> fields = {
      {"margin", &O::margin, Range::Closed(0, 1000), "dilation around each tracked mask, px"},
      {"keep_occluded", &O::keep_occluded, "occluded targets inhibit their last box"},
      {"occluded_search", &O::occluded_search, "... and the area their tracker searched them in"}};
  return fields;
}

Inhibition::Inhibition(const InhibitionOptions& options) : options_(options) {
  const int margin = options_.margin;
  kernel_ = cv::getStructuringElement(cv::MORPH_RECT, cv::Size(2 * margin + 1, 2 * margin + 1));
}

void Inhibition::Reset(cv::Size size) {
  inhibition_.create(size, CV_32FC1);
  inhibition_.setTo(0.f);
  covered_.create(size, CV_8UC1);
  covered_.setTo(0);
}

void Inhibition::AddTarget(const cv::Mat& own, const cv::Rect& box, const cv::Rect& image,
                           const cv::Mat& in_front, const cv::Mat& apart) {
  // The mask, dilated, within its box plus the margin.
  const int margin = options_.margin;
  const cv::Rect around =
      cv::Rect(box.x - margin, box.y - margin, box.width + 2 * margin, box.height + 2 * margin) &
      image;
  cv::Mat grown;
  cv::dilate(own(around), grown, kernel_);
  if (!in_front.empty()) grown.setTo(0, in_front(around));
  inhibition_(around).setTo(1.f, grown);
  if (apart.empty()) {
    covered_.setTo(255, own);
  } else {
    cv::Mat own_here;
    own(around).copyTo(own_here);
    own_here.setTo(0, apart(around));
    covered_(around).setTo(255, own_here);
  }
}

void Inhibition::AddOccluded(const cv::Rect& box, const cv::Rect& roi, const cv::Rect& image,
                             const cv::Mat& in_front, const cv::Mat& apart) {
  if (!options_.keep_occluded || box.empty()) return;
  const cv::Rect area = options_.occluded_search && !roi.empty() ? (box | roi) & image : box;
  if (area.empty()) return;
  inhibition_(area).setTo(1.f);
  if (!in_front.empty()) inhibition_(area).setTo(0.f, in_front(area));
  covered_(area).setTo(255);
  if (!apart.empty()) covered_(area).setTo(0, apart(area));
}

int Inhibition::Apply(const cv::Mat& saliency, const ObjectFiles& files) {
  // A remembered object's inhibition follows its predicted box and fades.
  files.Inhibit(&inhibition_);
  cv::subtract(cv::Scalar(1.f), inhibition_, inhibited_);
  cv::multiply(saliency, inhibited_, inhibited_);
  return cv::countNonZero(inhibition_);
}

void Inhibition::ReleaseShared() {
  ReleaseIfShared(&inhibition_);
  ReleaseIfShared(&inhibited_);
}

}  // namespace attend
