// The bounded mode (TrackerMode::kBounded; docs/TRACKING.md, "Modes"): the thesis's tracker
// for real footage. Its search weighs the overlap by a motion prior and the target's grey
// appearance and refines a coarse match at level 0; its refinement and box are bounded by
// where the target can plausibly be (BoundedRefinement); its template weights count by how
// distinctive their colour is; with the occlusion rules, a match that does not look like the
// target is an occlusion, and a target not found is searched for by its appearance.
#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "tracker/appearance_model.h"
#include "tracker/bounded_refinement.h"
#include "tracker/refinement.h"
#include "tracker/template_search.h"
#include "tracker/tracker_mode.h"

namespace attend {
namespace tracker_internal {

namespace {

class BoundedMode final : public ModePolicy {
 public:
  explicit BoundedMode(const TrackerOptions& options)
      : options_(options), appearance_(options), refinement_(options) {}

  TrackFrame Frame(const cv::Mat& bgr, const cv::Mat& cylinder) override {
    if (!options_.appearance) return {bgr, cylinder, cv::Mat()};
    cv::cvtColor(bgr, grey_, cv::COLOR_BGR2GRAY);
    return {bgr, cylinder, grey_};
  }

  // A user's box says where the object is, and a multi-coloured object's parts need not be
  // regions that lie mostly inside it.
  bool BoxIsTarget() const override { return true; }
  // An over-segmentation region mostly in the mask may still reach far beyond it.
  cv::Rect StartBounds(const cv::Mat& mask, cv::Size) const override {
    return cv::boundingRect(mask);
  }
  void Start(const cv::Mat& frame, const Hierarchy& h, const cv::Rect& built,
             Target* target) override {
    if (target->similarity != TrackSimilarity::kColour) return;
    target->roi = built;
    appearance_.LearnDistinct(h, target);
    if (options_.appearance) {
      cv::cvtColor(frame, grey_, cv::COLOR_BGR2GRAY);
      appearance_.LearnGrey(grey_, target);
    }
  }

  void Track(const TrackFrame& frame, const Hierarchy* h, int pyramid_levels, Target* target,
             TrackResult* result) override {
    std::vector<uint8_t> in_target(h != nullptr ? h->regions : 0, 0);
    Match match;
    bool correlated = false;  // whether the appearance scored the search
    if (h != nullptr) {
      correlated = appearance_.Correlate(frame.grey, *target, target->roi, &correlation_);
      match = Localise(*target, *h, correlated, &in_target);
    }
    result->overlap = match.overlap;
    // With the occlusion rules and an appearance model: a match whose correlation falls well
    // under the target's typical one is an occluder or the background taking its place.
    const double typical = target->appearance.typical_correlation;
    const bool judged = options_.occlusion && match.found && correlated && typical > 0.0;
    if (!match.found || (judged && match.correlation < options_.occlusion_ratio * typical)) {
      Missed(frame, target, result);
      return;
    }
    // Under occlusion_gate the box moves, but the target learns nothing of the place.
    const bool learn = !(judged && match.correlation < options_.occlusion_gate * typical);
    Found(frame, *h, match, pyramid_levels, &in_target, target, result);
    if (learn) Learn(frame, *h, correlated, match.correlation, target);
  }

 private:
  // Top-down localisation (4.2.3) with the bounded mode's scoring; a match at a coarse level
  // is then refined at level 0 (AtLevelZero). Marks the matched ROI vertices' regions in
  // `in_target` (the first stage of 4.2.4).
  Match Localise(const Target& target, const Hierarchy& h, bool correlated,
                 std::vector<uint8_t>* in_target) {
    SearchScoring scoring;
    scoring.t_colour = options_.t_colour;
    scoring.min_overlap = options_.bounded_min_overlap;
    scoring.motion_sigma = options_.motion_sigma;
    scoring.appearance = correlated ? &correlation_ : nullptr;
    scoring.appearance_share = options_.appearance_share;
    scoring.min_score = options_.min_score;
    const int working = WorkingLevel(target.levels, options_.working_area);
    for (int l = std::min(working, h.bip->num_levels() - 1); l >= 0; --l) {
      Match match = search_.SearchLevel(target, h, l, nullptr, scoring);
      if (!match.found) continue;
      if (l > 0) match = AtLevelZero(target, h, match, scoring);
      MarkMatched(target.levels[match.level], h, match.level, match.displacement, options_.t_colour,
                  in_target);
      return match;
    }
    return {};
  }

  // A match at a coarse level searched again at level 0 within one coarse cell of it, so that
  // the motion and the matched vertices are those of level 0 (a coarse cell of 2^l pixels
  // otherwise rounds the motion by up to 2^l pixels). Any overlap is accepted there.
  Match AtLevelZero(const Target& target, const Hierarchy& h, const Match& coarse,
                    SearchScoring scoring) {
    const int cell = 1 << coarse.level;
    const cv::Rect window(coarse.displacement.x * cell - cell, coarse.displacement.y * cell - cell,
                          2 * cell + 1, 2 * cell + 1);
    scoring.min_overlap = 0.0;
    const Match fine = search_.SearchLevel(target, h, 0, &window, scoring);
    if (fine.found) return fine;
    // The coarse match stands, but the correlation judged with it (occlusion rules, typical
    // correlation) is that of the level-0 search's best displacement when the appearance
    // scored one: so the tracker has always judged it, and its records depend on it.
    Match match = coarse;
    if (fine.scored) match.correlation = fine.correlation;
    return match;
  }

  // A target found at `match`: its box first (bounded and smoothed), then its pixels and
  // template inside that box only.
  void Found(const TrackFrame& frame, const Hierarchy& h, const Match& match, int pyramid_levels,
             std::vector<uint8_t>* in_target, Target* target, TrackResult* result) {
    const cv::Rect image(0, 0, frame.bgr.cols, frame.bgr.rows);
    const cv::Point shift(match.displacement.x << match.level, match.displacement.y << match.level);
    cv::Rect keep = target->roi;
    const cv::Rect plausible = refinement_.BoundTarget(h, *target, shift, image, in_target);
    PaintTarget(h, *in_target, plausible, frame.bgr.size(), &target->mask);
    const cv::Rect mask_box = cv::boundingRect(target->mask(plausible)) + plausible.tl();
    if (!mask_box.empty()) {
      cv::Rect2d smooth;
      keep = refinement_.SmoothBox(*target, shift, mask_box, plausible, image, &smooth);
      target->smooth = smooth;
      target->box = keep;
    }
    result->area =
        TakeFound(h, *in_target, keep, shift, pyramid_levels, options_, frame.bgr.size(), target);
    result->state = TrackState::kFound;
    result->level = match.level;
  }

  // What a found target learns of its looks: its distinctive colours and grey model, and,
  // when the appearance scored the search, the typical correlation (from the match's) and the
  // typical distinctiveness of its box.
  void Learn(const TrackFrame& frame, const Hierarchy& h, bool correlated, double correlation,
             Target* target) {
    appearance_.LearnDistinct(h, target);
    appearance_.LearnGrey(frame.grey, target);
    if (!correlated) return;
    TargetAppearance& a = target->appearance;
    a.typical_correlation = a.typical_correlation == 0.0
                                ? correlation
                                : 0.9 * a.typical_correlation + 0.1 * correlation;
    const double distinct = appearance_.MeanDistinct(frame, *target, target->box);
    if (distinct >= 0.0) {
      a.typical_distinct =
          a.typical_distinct == 0.0 ? distinct : 0.9 * a.typical_distinct + 0.1 * distinct;
    }
  }

  // A target not found (4.2.7). With the occlusion rules, one with an appearance model forgets
  // at occlusion_alpha: it outlasts an occlusion longer, and its model can find it again when
  // it comes out (Redetect).
  void Missed(const TrackFrame& frame, Target* target, TrackResult* result) {
    const float alpha =
        options_.occlusion && options_.appearance && !target->appearance.grey.empty()
            ? options_.occlusion_alpha
            : options_.alpha;
    TakeMissed(alpha, options_.EpsilonMaxPixels(frame.bgr.cols), target);
    if (!target->levels.empty()) Redetect(frame, target);
    result->state = target->levels.empty() ? TrackState::kLost : TrackState::kOccluded;
  }

  // A target not found is searched for by its grey model within `redetect_range` box sides of
  // its box; where it correlates by `redetect_ratio` of its typical correlation or more (and
  // its distinctive colours are there by the same share), the box and the template move there.
  // The target is still not found in this frame; the next frame's search starts there.
  void Redetect(const TrackFrame& frame, Target* target) {
    const TargetAppearance& a = target->appearance;
    if (a.typical_correlation <= 0.0) return;
    const cv::Rect& box = target->box;
    const int gx = static_cast<int>(std::lround(options_.redetect_range * box.width));
    const int gy = static_cast<int>(std::lround(options_.redetect_range * box.height));
    const cv::Rect area =
        cv::Rect(box.x - gx, box.y - gy, box.width + 2 * gx, box.height + 2 * gy) &
        cv::Rect(0, 0, frame.grey.cols, frame.grey.rows);
    CorrelationMap map;
    if (!appearance_.Correlate(frame.grey, *target, area, &map)) return;
    double best = 0.0;
    cv::Point at;
    cv::minMaxLoc(map.zncc, nullptr, &best, nullptr, &at);
    if (best < options_.redetect_ratio * a.typical_correlation) return;
    const cv::Point shift = area.tl() + at - box.tl();
    // The grey correlation does not see colour: the place must also have the target's
    // distinctive colours, by the same share of their typical mean.
    if (a.typical_distinct > 0.0 && appearance_.MeanDistinct(frame, *target, box + shift) <
                                        options_.redetect_ratio * a.typical_distinct) {
      return;
    }
    MoveTemplate(shift, &target->levels);
    target->box += shift;
    target->smooth.x += shift.x;
    target->smooth.y += shift.y;
    target->centroid += cv::Point2f(shift);
  }

  TrackerOptions options_;
  AppearanceModel appearance_;
  BoundedRefinement refinement_;
  TemplateSearch search_;
  // Buffers reused from call to call; no call reads what another left in them.
  cv::Mat grey_;                // the frame in grey (Frame, Start)
  CorrelationMap correlation_;  // the target's model over its ROI (Track)
};

}  // namespace

std::unique_ptr<ModePolicy> MakeBoundedMode(const TrackerOptions& options) {
  return std::make_unique<BoundedMode>(options);
}

}  // namespace tracker_internal
}  // namespace attend
