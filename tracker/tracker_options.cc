// TrackerOptions (tracker/tracker_options.h): its field table, its check and the names of its enums.
#include <algorithm>
#include <cmath>

#include "tracker/tracker_options.h"
#include "util/enum_table.h"

namespace attend {

int TrackerOptions::EpsilonPixels(int width) const {
  return std::max(1, static_cast<int>(std::lround(epsilon * width / 128.0)));
}

int TrackerOptions::EpsilonMaxPixels(int width) const {
  return std::max(EpsilonPixels(width), static_cast<int>(std::lround(epsilon_max * width / 128.0)));
}

namespace {

constexpr EnumTable<TrackerMode, 3> kTrackerModes = {{{
    {TrackerMode::kThesis, "thesis"},
    {TrackerMode::kBounded, "bounded"},
    {TrackerMode::kCorrelation, "correlation"},
}}};

}  // namespace

const OptionFields<TrackerOptions>& TrackerOptions::Fields() {
  using O = TrackerOptions;
  static const OptionFields<TrackerOptions> fields = {
      {"mode", EnumField<&O::mode, kTrackerModes>(),
       "thesis: chapter 4 as written; bounded: refinement and box bounded; correlation: a "
       "correlation filter with BIP masks (docs/TRACKING.md)"},
      {"t_colour", &O::t_colour, Range::Closed(0.001, 1000),
       "T_c: a template vertex matches a ROI vertex below this colour distance"},
      {"t_oversegment", &O::t_oversegment, Range::Closed(0.001, 1000),
       "T_co: T_max of the ROI's over-segmentation"},
      {"t_refine", &O::t_refine, Range::Closed(0, 1000),
       "T_cr: colour threshold of the target refinement"},
      {"alpha", &O::alpha, Range::Closed(0.001, 1), "forgetting constant of the template weights"},
      {"epsilon", &O::epsilon, Range::Closed(0, 1000),
       "ROI border, px at a width of 128 (scaled with the width)"},
      {"epsilon_max", &O::epsilon_max, Range::Closed(0, 1000),
       "the ROI border's maximum while the target is not found"},
      {"working_area", &O::working_area, Range::Closed(0.01, 1),
       "T_A: share of the template's area at the working level"},
      {"min_overlap", &O::min_overlap, Range::Closed(0.01, 1),
       "thesis: the weighted overlap that accepts a displacement"},
      {"bounded_min_overlap", &O::bounded_min_overlap, Range::Closed(0.01, 1),
       "bounded: the same, without appearance"},
      {"bound_growth", &O::bound_growth, Range::Closed(0, 1),
       "bounded: the target grows by at most this share of its box a frame, each side"},
      {"size_rate", &O::size_rate, Range::Closed(0, 1),
       "bounded: the box's size follows the mask's box by this share a frame"},
      {"centre_rate", &O::centre_rate, Range::Closed(0, 1),
       "bounded: the box's centre follows the mask's box by this share a frame"},
      {"distinctive_weights", &O::distinctive_weights,
       "bounded: template weights scaled by how distinctive their colour is"},
      {"distinct_rate", &O::distinct_rate, Range::Closed(0, 1),
       "bounded: the distinctiveness table's update rate; 0: the first frame's"},
      {"motion_sigma", &O::motion_sigma, Range::Closed(0, 100),
       "bounded: the motion prior's sigma, box sides; 0: off"},
      {"appearance", &O::appearance, "bounded: match the target's grey appearance too (ZNCC)"},
      {"appearance_share", &O::appearance_share, Range::Closed(0, 1),
       "bounded: the appearance's share of a displacement's score"},
      {"appearance_rate", &O::appearance_rate, Range::Closed(0, 1),
       "bounded: the appearance model's update rate"},
      {"min_score", &O::min_score, Range::Closed(0.01, 1),
       "bounded: the score that accepts a displacement, with appearance"},
      {"redetect_range", &O::redetect_range, Range::Closed(0, 10),
       "bounded: a target not found is searched for within this many box sides"},
      {"redetect_ratio", &O::redetect_ratio, Range::Closed(0.01, 1),
       "bounded: ... and moves where it matches by this share of its typical correlation"},
      {"occlusion", &O::occlusion,
       "bounded: the occlusion rules (occlusion_gate, occlusion_ratio, occlusion_alpha)"},
      {"occlusion_gate", &O::occlusion_gate, Range::Closed(0, 1),
       "bounded: a match under this share of the typical correlation teaches nothing; 0: off"},
      {"occlusion_ratio", &O::occlusion_ratio, Range::Closed(0, 1),
       "bounded: a match under this share of the typical correlation is an occlusion; 0: off"},
      {"occlusion_alpha", &O::occlusion_alpha, Range::Closed(0.001, 1),
       "bounded: the template's forgetting constant while a target with appearance is missed"},
      CodeOnly<O>({"pyramid_parts", &O::pyramid_parts,
                   "the ROIs' pyramid built in parts (true) or whole; the same results"})};
  return fields;
}

std::string TrackerOptions::Check() const {
  const std::string error = CheckFieldRanges(*this, Fields());
  if (!error.empty()) return error;
  if (!(epsilon_max >= epsilon)) return "epsilon_max must be >= epsilon";
  return "";
}

const char* TrackerModeName(TrackerMode mode) { return kTrackerModes.Name(mode); }

const char* TrackStateName(TrackState state) {
  switch (state) {
    case TrackState::kFound:
      return "found";
    case TrackState::kOccluded:
      return "occluded";
    case TrackState::kLost:
      return "lost";
  }
  return "lost";
}

}  // namespace attend
