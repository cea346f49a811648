#include "semiattentive/select_options.h"

#include "util/enum_table.h"

namespace attend {

namespace {

constexpr EnumTable<CandidateOrder, 3> kOrders = {{{
    {CandidateOrder::kMass, "mass"},
    {CandidateOrder::kPeak, "peak"},
    {CandidateOrder::kMean, "mean"},
}}};

constexpr EnumTable<SeedKind, 3> kSeedKinds = {{{
    {SeedKind::kRegion, "region"},
    {SeedKind::kObject, "object"},
    {SeedKind::kDetection, "detection"},
}}};

}  // namespace

const char* SeedKindName(SeedKind seed) { return kSeedKinds.Name(seed); }

const OptionFields<SelectOptions>& SelectOptions::Fields() {
  using O = SelectOptions;
  static const OptionFields<SelectOptions> fields = {
      {"min_saliency", &O::min_saliency, Range::Closed(0, 1),
       "a candidate region's mean inhibited saliency at least this"},
      {"min_area", &O::min_area, Range::Closed(1, 1e8), "a candidate's area at least this, px"},
      {"max_new", &O::max_new, Range::Closed(1, 1000), "targets started in one frame"},
      {"max_targets", &O::max_targets, Range::Closed(1, 1000), "targets active at once"},
      {"max_area_fraction", &O::max_area_fraction, Range::Closed(0.001, 1),
       "a colour region larger than this share of the image is background"},
      {"order", EnumField<&O::order, kOrders>(),
       "what ranks the candidates: mass (mean inhibited saliency x area, the thesis), peak "
       "(highest inhibited saliency), mean"},
      {"proximity", &O::proximity, Range::Closed(0, 10),
       "> 0: each candidate's score x exp(-d^2 / 2 s^2), d its peak's distance from the last "
       "target started, s this share of the image diagonal; 0: off"},
      {"faces_first", &O::faces_first,
       "candidates whose peak lies in a face detection (the faces channel) come first"},
      {"max_inhibited_fraction", &O::max_inhibited_fraction, Range::Closed(0.001, 1),
       "no new target while the inhibition would cover more of the image; 1: no bound"},
      {"saliency_t_max", &O::saliency_t_max, Range::Closed(0.001, 1000),
       "T_max of the BIP that segments the saliency map (saliency x 255)"},
      {"seed", EnumField<&O::seed, kSeedKinds>(),
       "what a candidate starts as: its colour region, the object around it, or a detection"},
      {"seed_share", &O::seed_share, Range::Closed(0.01, 1),
       "object/detection: a colour region joins the seed when this share of it lies inside"},
      {"seed_level", &O::seed_level, Range::Closed(0.01, 1),
       "object: the salient region is where saliency is at least this times the mean"},
      {"detection_taken", &O::detection_taken, Range::Closed(0, 1),
       "detection: a detection an active target covers by this share belongs to it"},
      {"detected_only", &O::detected_only,
       "detection: a candidate under no detection starts nothing"},
      {"reanchor_min_iou", &O::reanchor_min_iou, Range::Closed(0, 1),
       "a found target restarts on a detection overlapping it at least this (IoU); 0: never"},
      {"reanchor_max_iou", &O::reanchor_max_iou, Range::Closed(0, 1), "... and below this IoU"},
      {"reanchor_min_similarity", &O::reanchor_min_similarity, Range::Closed(0, 1),
       "... and when the detection looks at least this like the target; 0: any look"},
      {"every_detection", &O::every_detection,
       "detection: every free detection starts a target, the most salient first"},
      {"detection_box", &O::detection_box,
       "a recognised target's box is its detection's, its tracker's only in between"},
      {"group_min_speed", &O::group_min_speed, Range::Closed(0, 1000),
       "object: motion grouping above this speed, px a frame; 0: off"},
      {"group_flow_tolerance", &O::group_flow_tolerance, Range::Closed(0, 10),
       "motion grouping: a region joins when its flow differs by at most this times the speed"},
      {"background", &O::background,
       "the ground, regions without measured depth, regions along the border and large ones "
       "are no candidates and no targets (semiattentive/background.h); false: the thesis's"},
      {"border_share", &O::border_share, Range::Closed(0, 1),
       "background: a colour region on this share of the image's border is background; 1: off"},
      {"min_measured", &O::min_measured, Range::Closed(0, 1),
       "background, stereo: a colour region with less of its pixels measured has no depth"},
      {"ground_share", &O::ground_share, Range::Closed(0, 1),
       "background, stereo: a region this much of whose measured pixels are ground is ground"},
      {"max_height", &O::max_height, Range::Closed(0, 1000),
       "background, stereo with a baseline: a region higher above the ground (m) is background; "
       "0: off"},
      {"group_depth", &O::group_depth, Range::Closed(0, 1),
       "object, stereo: neighbouring regions within this share of the seed's disparity join "
       "it; 0: off"}};
  return fields;
}

}  // namespace attend
