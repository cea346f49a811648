// What TrackerMode::kBounded adds to the thesis's tracker (tracker_impl.h; docs/TRACKING.md,
// "Modes"): the distinctive colour weights, the grey appearance and its redetection, the
// plausible box that bounds the refinement and the smoothed box.
#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "tracker/tracker_impl.h"
#include "util/error.h"

namespace attend {

using namespace tracker_internal;

void MultiTracker::Impl::LearnDistinct(const Hierarchy& h, Target* target) const {
  if (!options.distinctive_weights || target->similarity != TrackSimilarity::kColour ||
      target->mask.empty()) {
    return;
  }
  fg_.assign(kColourBins, 0.f);
  bg_.assign(kColourBins, 0.f);
  const BipLevel& base = h.bip->level(0);
  const cv::Rect roi = target->roi & cv::Rect(h.origin, h.size);
  float nf = 0.f, nb = 0.f;
  for (int y = roi.y; y < roi.y + roi.height; ++y) {
    const uchar* m = target->mask.ptr<uchar>(y);
    const int row = (y - h.origin.y) * base.cols - h.origin.x;
    for (int x = roi.x; x < roi.x + roi.width; ++x) {
      const int cell = row + x;
      const int bin = ColourBin(base.Feature(cell));
      if (m[x]) {
        fg_[bin] += 1.f, nf += 1.f;
      } else if (!target->box.contains({x, y})) {
        bg_[bin] += 1.f, nb += 1.f;
      }
    }
  }
  if (nf <= 0.f) return;
  const bool first = target->distinct.empty();
  if (first) target->distinct.assign(kColourBins, 1.f);
  for (int b = 0; b < kColourBins; ++b) {
    const float f = fg_[b] / nf, g = nb > 0.f ? bg_[b] / nb : 0.f;
    const float d = f + g > 0.f ? f / (f + g) : 0.5f;
    float& w = target->distinct[b];
    w = first ? d : (1.f - options.distinct_rate) * w + options.distinct_rate * d;
  }
}

bool MultiTracker::Impl::Correlate(const Target& target, const cv::Rect& area,
                                   cv::Mat* correlation) const {
  if (options.mode != TrackerMode::kBounded || !options.appearance || target.appearance.empty() ||
      grey_.empty()) {
    return false;
  }
  const cv::Rect& box = target.box;
  if (box.width < 2 || box.height < 2 || area.width < box.width || area.height < box.height) {
    return false;
  }
  cv::resize(target.appearance, model_, box.size(), 0, 0, cv::INTER_LINEAR);
  grey_(area).convertTo(patch_, CV_32F);
  cv::matchTemplate(patch_, model_, *correlation, cv::TM_CCOEFF_NORMED);
  return true;
}

double MultiTracker::Impl::CorrelationAt(const cv::Point& d, int l) const {
  const int x = (d.x << l) + box_to_roi_.x, y = (d.y << l) + box_to_roi_.y;
  if (x < 0 || y < 0 || x >= correlation_.cols || y >= correlation_.rows) return 0.0;
  return correlation_.at<float>(y, x);
}

double MultiTracker::Impl::MeanDistinct(const Target& target, const cv::Rect& box) const {
  const cv::Rect inside = box & cv::Rect(0, 0, frame_.cols, frame_.rows);
  if (target.distinct.empty() || inside.empty()) return -1.0;
  // The caller's cylinder image when it gave one, else converted here (the same values).
  cv::Mat cylinder;
  if (frame_cylinder_.empty()) {
    BgrToCylinder(frame_(inside), &cylinder_);
    cylinder = cylinder_;
  } else {
    cylinder = frame_cylinder_(inside);
  }
  double sum = 0.0;
  for (int y = 0; y < cylinder.rows; ++y) {
    const float* f = cylinder.ptr<float>(y);
    for (int x = 0; x < cylinder.cols; ++x) sum += target.distinct[ColourBin(f + 3 * x)];
  }
  return sum / inside.area();
}

void MultiTracker::Impl::LearnAppearance(Target* target) const {
  if (!options.appearance || target->similarity != TrackSimilarity::kColour || grey_.empty()) {
    return;
  }
  const cv::Rect box = target->box & cv::Rect(0, 0, grey_.cols, grey_.rows);
  if (box.width < 2 || box.height < 2) return;
  grey_(box).convertTo(patch_, CV_32F);
  if (!target->appearance_judged) {
    target->appearance_judged = true;
    // A flat patch's correlation is noise (and OpenCV gives a flat model 1 everywhere): a
    // target without texture when it starts has no appearance model.
    cv::Scalar mean, deviation;
    cv::meanStdDev(patch_, mean, deviation);
    if (deviation[0] >= kMinAppearanceDeviation) target->appearance = patch_.clone();
    return;
  }
  if (target->appearance.empty()) return;
  cv::resize(patch_, patch_, target->appearance.size(), 0, 0, cv::INTER_AREA);
  cv::addWeighted(target->appearance, 1.0 - options.appearance_rate, patch_,
                  options.appearance_rate, 0.0, target->appearance);
}

void MultiTracker::Impl::Redetect(Target* target) {
  if (target->typical_correlation <= 0.0) return;
  const cv::Rect& box = target->box;
  const int gx = static_cast<int>(std::lround(options.redetect_range * box.width));
  const int gy = static_cast<int>(std::lround(options.redetect_range * box.height));
  const cv::Rect area = cv::Rect(box.x - gx, box.y - gy, box.width + 2 * gx, box.height + 2 * gy) &
                        cv::Rect(0, 0, grey_.cols, grey_.rows);
  cv::Mat correlation;
  if (!Correlate(*target, area, &correlation)) return;
  double best = 0.0;
  cv::Point at;
  cv::minMaxLoc(correlation, nullptr, &best, nullptr, &at);
  if (best < options.redetect_ratio * target->typical_correlation) return;
  const cv::Point shift = area.tl() + at - box.tl();
  // The grey correlation does not see colour: the place must also have the target's
  // distinctive colours, by the same share of their typical mean.
  if (target->typical_distinct > 0.0 &&
      MeanDistinct(*target, box + shift) < options.redetect_ratio * target->typical_distinct) {
    return;
  }
  for (size_t l = 0; l < target->levels.size(); ++l) {
    target->levels[l].cells.x +=
        static_cast<int>(std::lround(shift.x / static_cast<double>(1 << l)));
    target->levels[l].cells.y +=
        static_cast<int>(std::lround(shift.y / static_cast<double>(1 << l)));
  }
  target->box += shift;
  target->smooth.x += shift.x;
  target->smooth.y += shift.y;
  target->centroid += cv::Point2f(shift);
}

cv::Rect MultiTracker::Impl::BoundTarget(const Hierarchy& h, const Target& target, cv::Point shift,
                                         const cv::Rect& image,
                                         std::vector<uint8_t>* in_target) const {
  const cv::Rect moved = target.box + shift;
  const int gx = std::max(2, static_cast<int>(std::lround(options.bound_growth * moved.width)));
  const int gy = std::max(2, static_cast<int>(std::lround(options.bound_growth * moved.height)));
  const cv::Rect plausible =
      cv::Rect(moved.x - gx, moved.y - gy, moved.width + 2 * gx, moved.height + 2 * gy) &
      target.roi & image;
  const std::vector<uint8_t> matched = *in_target;
  Refine(h, plausible, in_target);
  region_inside_.assign(h.regions, 0);
  region_all_.assign(h.regions, 0);
  const BipLevel& base = h.bip->level(0);
  const cv::Rect roi = target.roi & cv::Rect(h.origin, h.size);
  for (int y = roi.y; y < roi.y + roi.height; ++y) {
    const int row = (y - h.origin.y) * base.cols - h.origin.x;
    const bool y_in = y >= moved.y && y < moved.y + moved.height;
    for (int x = roi.x; x < roi.x + roi.width; ++x) {
      const int cell = row + x;
      if (!base.hom[cell]) continue;
      const int r = h.region[0][cell];
      if (r < 0 || !(*in_target)[r]) continue;
      ++region_all_[r];
      if (y_in && x >= moved.x && x < moved.x + moved.width) ++region_inside_[r];
    }
  }
  bool any = false;
  for (int r = 0; r < h.regions; ++r) {
    if (!(*in_target)[r]) continue;
    (*in_target)[r] = 2 * region_inside_[r] >= region_all_[r];
    any = any || (*in_target)[r];
  }
  // When every region reaches out, the matched regions are kept, cut to the box.
  if (!any) *in_target = matched;
  return plausible;
}

cv::Rect MultiTracker::Impl::SmoothBox(const Target& target, cv::Point shift, cv::Rect mask_box,
                                       const cv::Rect& plausible, const cv::Rect& image,
                                       cv::Rect2d* smooth) const {
  const cv::Rect moved = target.box + shift;
  // The unrounded box moved as the rounded one: only its size and sub-pixel offset carry.
  const cv::Rect2d last = target.smooth.area() > 0 ? target.smooth : cv::Rect2d(target.box);
  const cv::Rect2d moved_smooth(last.x + shift.x, last.y + shift.y, last.width, last.height);
  int x0 = mask_box.x, y0 = mask_box.y;
  int x1 = mask_box.x + mask_box.width, y1 = mask_box.y + mask_box.height;
  if (x0 <= plausible.x && plausible.x > 0) x0 = std::max(x0, moved.x);
  if (y0 <= plausible.y && plausible.y > 0) y0 = std::max(y0, moved.y);
  if (x1 >= plausible.x + plausible.width && x1 < image.width) {
    x1 = std::min(x1, moved.x + moved.width);
  }
  if (y1 >= plausible.y + plausible.height && y1 < image.height) {
    y1 = std::min(y1, moved.y + moved.height);
  }
  if (x1 <= x0 || y1 <= y0) return moved & image;
  const double rate = options.size_rate;
  const double w = (1 - rate) * moved_smooth.width + rate * (x1 - x0);
  const double hgt = (1 - rate) * moved_smooth.height + rate * (y1 - y0);
  const double crate = options.centre_rate;
  const double cx =
      (1 - crate) * (moved_smooth.x + moved_smooth.width / 2.0) + crate * (x0 + x1) / 2.0;
  const double cy =
      (1 - crate) * (moved_smooth.y + moved_smooth.height / 2.0) + crate * (y0 + y1) / 2.0;
  *smooth = cv::Rect2d(cx - w / 2, cy - hgt / 2, std::max(1.0, w), std::max(1.0, hgt));
  cv::Rect box(static_cast<int>(std::lround(cx - w / 2)),
               static_cast<int>(std::lround(cy - hgt / 2)),
               std::max(1, static_cast<int>(std::lround(w))),
               std::max(1, static_cast<int>(std::lround(hgt))));
  box &= image;
  return box.empty() ? (moved & image) : box;
}

}  // namespace attend
