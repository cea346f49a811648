#include "tracker/appearance_model.h"

#include <opencv2/imgproc.hpp>

#include "colour/colour.h"
#include "tracker/target.h"

namespace attend {
namespace tracker_internal {

void AppearanceModel::LearnDistinct(const Hierarchy& h, Target* target) {
  if (!options_.distinctive_weights || target->similarity != TrackSimilarity::kColour ||
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
  std::vector<float>& distinct = target->appearance.distinct;
  const bool first = distinct.empty();
  if (first) distinct.assign(kColourBins, 1.f);
  for (int b = 0; b < kColourBins; ++b) {
    const float f = fg_[b] / nf, g = nb > 0.f ? bg_[b] / nb : 0.f;
    const float d = f + g > 0.f ? f / (f + g) : 0.5f;
    float& w = distinct[b];
    w = first ? d : (1.f - options_.distinct_rate) * w + options_.distinct_rate * d;
  }
}

void AppearanceModel::LearnGrey(const cv::Mat& grey, Target* target) {
  if (!options_.appearance || target->similarity != TrackSimilarity::kColour || grey.empty()) {
    return;
  }
  const cv::Rect box = target->box & cv::Rect(0, 0, grey.cols, grey.rows);
  if (box.width < 2 || box.height < 2) return;
  grey(box).convertTo(patch_, CV_32F);
  TargetAppearance& appearance = target->appearance;
  if (!appearance.judged) {
    appearance.judged = true;
    // A flat patch's correlation is noise (and OpenCV gives a flat model 1 everywhere): a
    // target without texture when it starts has no appearance model.
    cv::Scalar mean, deviation;
    cv::meanStdDev(patch_, mean, deviation);
    if (deviation[0] >= kMinAppearanceDeviation) appearance.grey = patch_.clone();
    return;
  }
  if (appearance.grey.empty()) return;
  cv::resize(patch_, patch_, appearance.grey.size(), 0, 0, cv::INTER_AREA);
  cv::addWeighted(appearance.grey, 1.0 - options_.appearance_rate, patch_, options_.appearance_rate,
                  0.0, appearance.grey);
}

bool AppearanceModel::Correlate(const cv::Mat& grey, const Target& target, const cv::Rect& area,
                                CorrelationMap* map) {
  if (!options_.appearance || target.appearance.grey.empty() || grey.empty()) return false;
  const cv::Rect& box = target.box;
  if (box.width < 2 || box.height < 2 || area.width < box.width || area.height < box.height) {
    return false;
  }
  cv::resize(target.appearance.grey, model_, box.size(), 0, 0, cv::INTER_LINEAR);
  grey(area).convertTo(patch_, CV_32F);
  cv::matchTemplate(patch_, model_, map->zncc, cv::TM_CCOEFF_NORMED);
  map->box_in_area = box.tl() - area.tl();
  return true;
}

double AppearanceModel::MeanDistinct(const TrackFrame& frame, const Target& target,
                                     const cv::Rect& box) {
  const cv::Rect inside = box & cv::Rect(0, 0, frame.bgr.cols, frame.bgr.rows);
  const std::vector<float>& distinct = target.appearance.distinct;
  if (distinct.empty() || inside.empty()) return -1.0;
  // The caller's cylinder image when it gave one, else converted here (the same values).
  cv::Mat cylinder;
  if (frame.cylinder.empty()) {
    BgrToCylinder(frame.bgr(inside), &cylinder_);
    cylinder = cylinder_;
  } else {
    cylinder = frame.cylinder(inside);
  }
  double sum = 0.0;
  for (int y = 0; y < cylinder.rows; ++y) {
    const float* f = cylinder.ptr<float>(y);
    for (int x = 0; x < cylinder.cols; ++x) sum += distinct[ColourBin(f + 3 * x)];
  }
  return sum / inside.area();
}

}  // namespace tracker_internal
}  // namespace attend
