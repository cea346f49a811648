#include "semiattentive/recognition.h"

#include <algorithm>

#include "util/assignment.h"
#include "util/box.h"

namespace attend {

Recogniser::Recogniser(const SelectOptions& select, const DropOptions& drop, float label_overlap,
                       Reidentifier* reidentifier)
    : select_(select),
      unrecognised_frames_(drop.unrecognised_frames),
      label_overlap_(label_overlap),
      reidentifier_(reidentifier) {}

std::vector<int> Recogniser::MatchDetections(const std::vector<TrackResult>& results,
                                             const FollowedTargets& targets,
                                             const std::vector<Detection>& detections,
                                             const cv::Rect& image) const {
  std::vector<int> detection_of(results.size(), -1);
  if (detections.empty()) return detection_of;
  std::vector<int> rows;
  std::vector<cv::Rect> target_boxes, detection_boxes;
  for (size_t r = 0; r < results.size(); ++r) {
    const TrackResult& result = results[r];
    const FollowedTarget* target = targets.OfTracker(result.id);
    if (target == nullptr || target->skin || result.state != TrackState::kFound) continue;
    rows.push_back(static_cast<int>(r));
    target_boxes.push_back(result.box & image);
  }
  for (const Detection& detection : detections) detection_boxes.push_back(detection.box);
  const double min_iou = select_.reanchor_min_iou > 0.f ? select_.reanchor_min_iou : 0.3;
  for (const auto& [row, column] : MatchBoxes(target_boxes, detection_boxes, min_iou)) {
    detection_of[rows[row]] = column;
  }
  return detection_of;
}

Recognition Recogniser::Recognise(const cv::Mat& bgr, const Segmentation& segmentation,
                                  const std::vector<Detection>& detections, const cv::Rect& box,
                                  int detection, SeedMaker* seeds, FollowedTarget* target,
                                  Seed* seed) const {
  int on = detection;
  const bool reanchor = on >= 0 && select_.reanchor_min_iou > 0.f &&
                        BoxIou(box, detections[on].box) < select_.reanchor_max_iou;
  if (reanchor) seeds->FromBox(segmentation, detections[on].box, seed);
  const int seed_area = reanchor ? static_cast<int>(seed->area) : 0;
  if (reanchor && select_.reanchor_min_similarity > 0.f && !target->appearance.empty() &&
      seed_area > 0) {
    ObjectAppearance seen = ObjectAppearance::Of(bgr, seed->mask, detections[on].box);
    if (reidentifier_ != nullptr && !target->appearance.embedding.empty()) {
      seen.embedding = reidentifier_->Embed(bgr, detections[on].box);
    }
    // The detection is someone else's: this target is not recognised.
    if (target->appearance.Similarity(seen) < select_.reanchor_min_similarity) on = -1;
  }
  Recognition recognition;
  if (on >= 0) {
    recognition.detection = on;
    recognition.reanchor = reanchor && seed_area >= select_.min_area;
    target->unrecognised = 0;
  } else if (!target->label.empty() && unrecognised_frames_ > 0 &&
             ++target->unrecognised >= unrecognised_frames_) {
    recognition.unrecognised = true;
  }
  return recognition;
}

std::string Recogniser::LabelOf(const cv::Rect& box,
                                const std::vector<Detection>& detections) const {
  std::string label;
  double best = label_overlap_;
  for (const Detection& detection : detections) {
    // Of both boxes: a target on half a person is labelled by the person's detection, a box
    // on the pavement that one detection crosses is not.
    const int larger = std::max(box.area(), detection.box.area());
    const double overlap =
        larger > 0 ? static_cast<double>((box & detection.box).area()) / larger : 0.0;
    if (overlap >= best && !detection.label.empty()) best = overlap, label = detection.label;
  }
  return label;
}

}  // namespace attend
