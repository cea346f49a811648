// The thesis's tracker (chapter 4) as written: the top-down localisation of the template
// (4.2.3), the refinement of the matched regions by their neighbours (4.2.4), the target's box
// from its pixels, and the template update with forgetting (4.2.5-4.2.7).
#include <algorithm>
#include <opencv2/imgproc.hpp>

#include "tracker/refinement.h"
#include "tracker/template_search.h"
#include "tracker/tracker_mode.h"

namespace attend {
namespace tracker_internal {

namespace {

class ThesisMode final : public ModePolicy {
 public:
  explicit ThesisMode(const TrackerOptions& options) : options_(options) {}

  TrackFrame Frame(const cv::Mat& bgr, const cv::Mat& cylinder) override {
    return {bgr, cylinder, cv::Mat()};
  }

  bool BoxIsTarget() const override { return false; }
  cv::Rect StartBounds(const cv::Mat&, cv::Size frame_size) const override {
    return {0, 0, frame_size.width, frame_size.height};
  }
  void Start(const cv::Mat&, const Hierarchy&, const cv::Rect&, Target*) override {}

  void Track(const TrackFrame& frame, const Hierarchy* h, int pyramid_levels, Target* target,
             TrackResult* result) override {
    std::vector<uint8_t> in_target(h != nullptr ? h->regions : 0, 0);
    const Match match = h == nullptr ? Match() : Localise(*target, *h, &in_target);
    result->overlap = match.overlap;
    if (!match.found) {
      // 4.2.7: the template forgets at alpha; lost once it is empty.
      TakeMissed(options_.alpha, options_.EpsilonMaxPixels(frame.bgr.cols), target);
      result->state = target->levels.empty() ? TrackState::kLost : TrackState::kOccluded;
      return;
    }
    const cv::Point shift(match.displacement.x << match.level, match.displacement.y << match.level);
    Refine(*h, target->roi, options_.t_refine, &in_target);
    result->area = TakeFound(*h, in_target, target->roi, shift, pyramid_levels, options_,
                             frame.bgr.size(), target);
    if (result->area > 0) {
      target->box = cv::boundingRect(target->mask(target->roi)) + target->roi.tl();
    }
    result->state = TrackState::kFound;
    result->level = match.level;
  }

 private:
  // Top-down localisation (4.2.3): from the working level down, the first level whose best
  // displacement passes `min_overlap`; its matched ROI vertices' regions are marked in
  // `in_target` (the first stage of 4.2.4).
  Match Localise(const Target& target, const Hierarchy& h, std::vector<uint8_t>* in_target) {
    SearchScoring scoring;
    scoring.t_colour = options_.t_colour;
    scoring.min_overlap = options_.min_overlap;
    const int working = WorkingLevel(target.levels, options_.working_area);
    for (int l = std::min(working, h.bip->num_levels() - 1); l >= 0; --l) {
      const Match match = search_.SearchLevel(target, h, l, nullptr, scoring);
      if (!match.found) continue;
      MarkMatched(target.levels[l], h, l, match.displacement, options_.t_colour, in_target);
      return match;
    }
    return {};
  }

  TrackerOptions options_;
  TemplateSearch search_;
};

}  // namespace

std::unique_ptr<ModePolicy> MakeThesisMode(const TrackerOptions& options) {
  return std::make_unique<ThesisMode>(options);
}

}  // namespace tracker_internal
}  // namespace attend
