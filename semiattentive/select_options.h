// The `select` section of the configuration: how the attention stage chooses what to attend
// next and what a new target starts from (thesis 5.1.2, SPEC 2.4). One struct, because one
// section holds these keys; each group of fields below is read by one step of the stage:
//   candidates (semiattentive/candidates.h)       min_saliency, min_area, saliency_t_max,
//                                                  order, proximity, faces_first
//   the selection (semiattentive/attention.cc)     max_new, max_targets, max_area_fraction,
//                                                  max_inhibited_fraction
//   seeds (semiattentive/seeds.h)                  seed, seed_share, seed_level,
//                                                  detection_taken, detected_only
//   recognition (semiattentive/recognition.h)      reanchor_min_iou, reanchor_max_iou,
//                                                  reanchor_min_similarity
//   motion grouping (semiattentive/motion_grouping.h)  group_min_speed, group_flow_tolerance
// The release rules (semiattentive/release.h) also read min_area and max_area_fraction.
#pragma once

#include "util/option_fields.h"

namespace attend {

// What ranks the candidates (SelectOptions::order): the thesis's mean inhibited saliency times
// area (`mass`), the region's highest inhibited saliency (`peak`, a winner-take-all on the map),
// or its mean (`mean`).
enum class CandidateOrder { kMass, kPeak, kMean };

// What a candidate starts as (SelectOptions::seed).
enum class SeedKind { kRegion, kObject, kDetection };
// "region", "object", "detection" (the select.seed key).
const char* SeedKindName(SeedKind seed);

struct SelectOptions {
  float min_saliency = 0.2f;  // mean inhibited saliency of a candidate region, 0..1
  int min_area = 120;         // pixels, at the working size
  int max_new = 2;            // select.max_new: its row in Fields() describes it
  int max_targets = 12;       // targets active at once
  // A colour region larger than this share of the image is background, never a target.
  float max_area_fraction = 0.2f;
  // The order of attention (semiattentive/candidates.h, RankCandidates): what ranks the
  // candidates; then, with `proximity` > 0, each score times exp(-d^2 / (2 s^2)), d the distance
  // of the candidate's peak from the last target started (where attention is), s `proximity`
  // times the image's diagonal; then, with `faces_first`, the candidates whose peak lies in a
  // `face` detection before the others. The thesis: mass, 0, false.
  CandidateOrder order = CandidateOrder::kMass;
  float proximity = 0.f;
  bool faces_first = false;
  // No new target starts while the inhibition (with the new region) would cover more than
  // this share of the image; 1: no bound (the thesis's).
  float max_inhibited_fraction = 0.3f;
  // T_max of the BIP that segments the saliency map, in saliency units times 255.
  float saliency_t_max = 40.f;
  // What a candidate starts as: "region", the colour region it overlaps most (thesis 5.1.2),
  // or "object", that region together with every colour region of which at least
  // `seed_share` lies inside the candidate's salient region (an object of several colours,
  // such as a person's coat, trousers and head). The object's area is bounded as a region's.
  // "detection": where the candidate's most salient pixel lies in a top-down channel's
  // detection box (features/detectors.h), the colour regions of which at least `seed_share`
  // lies inside that box (a whole person), and a candidate inside a detection that an active
  // target already covers by `detection_taken` of its box is part of that target, not a new
  // one; elsewhere as "object".
  SeedKind seed = SeedKind::kRegion;
  float detection_taken = 0.3f;
  // "detection" only: a candidate under no detection starts nothing (the channels are told
  // where it is, through the look regions, and recognise it in the next frames), so that
  // every target is a recognised object; false: it starts as an "object" seed.
  bool detected_only = false;
  // Recognition keeps a target on its object: a found target whose box and a detection's
  // overlap with IoU in [reanchor_min_iou, reanchor_max_iou) starts again from that
  // detection's colour regions, under its own id (its tracker had slid off part of the
  // object). 0: never.
  float reanchor_min_iou = 0.f;
  float reanchor_max_iou = 0.75f;
  // ... and only when what the detection's seed looks like (ObjectAppearance::Similarity)
  // is at least this like what the target looked like on its object: a target that slid
  // onto the person beside it is not restarted on them (it is left as it is, unrecognised).
  // 0: any look.
  float reanchor_min_similarity = 0.f;
  // A recognised target is where its detection is: its box in the records (and in its
  // object file) is the detection's box, and its tracker's box only in the frames no detection
  // is on it. false: always the tracker's (its mask's bounding box).
  bool detection_box = false;
  // "detection" only: after the candidates, every detection that no target is on and no
  // followed target covers starts a target too, the most salient (mean inhibited saliency
  // over its box) first, within select.max_new and select.max_targets: attention still
  // orders them, but a recognised object needs no salient region of its own. false: only
  // detections under a candidate's most salient pixel start targets.
  bool every_detection = false;
  float seed_share = 0.5f;
  // object: the candidate's salient region is the connected area around its most salient
  // pixel where the inhibited saliency is at least this times the candidate's mean.
  float seed_level = 0.5f;
  // object: motion grouping. Where the proto-object moves at least this fast (px a frame, its
  // regions' mean dense optical flow from the previous frame, OpenCV's DIS), the colour
  // regions next to it that move alike join it, region by region outwards: a region whose mean
  // flow differs from the proto-object's by at most group_flow_tolerance times its speed.
  // 0: off (the thesis's stage has no motion).
  float group_min_speed = 0.f;
  float group_flow_tolerance = 0.5f;
  // Background is not a candidate (semiattentive/background.h): the colour regions on the
  // ground plane (at least `ground_share` of their measured pixels), those with less than
  // `min_measured` of their pixels measured by the stereo matcher (the sky, blank walls), those
  // on at least `border_share` of the image's border (the boundary prior) and those larger than
  // max_area_fraction take no part in candidates, seeds or targets; a found target mostly on
  // them is released ("background"). false: the thesis's stage.
  bool background = true;
  float border_share = 0.25f;
  float min_measured = 0.15f;
  float ground_share = 0.5f;
  // Stereo with a known baseline and a ground plane: a colour region whose measured pixels lie
  // on average higher than this above the ground (metres) is background: tree tops, the upper
  // floors of buildings, the sky when measured. What a street holds (cars, cyclists, people)
  // stands on the ground below it. 0: off.
  float max_height = 2.5f;
  // object seeds, stereo: the neighbouring colour regions whose mean measured disparity lies
  // within this share of the seed's join it, region by region outwards (a proto-object: one
  // object at one depth, off the ground). 0: off.
  float group_depth = 0.1f;
  // The fields (util/option_fields.h), for AttentionOptions::Check and the configuration's
  // `select` section.
  static const OptionFields<SelectOptions>& Fields();
};

}  // namespace attend
