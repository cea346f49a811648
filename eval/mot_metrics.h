// The MOTChallenge measures of a run against ground-truth objects (SPEC 4, `attend eval`), so
// that attend can be set beside a tracker's published numbers, and the attention measures that
// use the same one-to-one match. docs/ATTENTION.md ("The MOTChallenge measures") says what each
// means for an attention system, which looks at a few objects at a time.
//
// Per frame, the visible targets (Visible: new, tracked, resumed) are matched one to one to the
// counted objects (visible_fraction >= `min_visible`, box area >= `min_area`, the rule of
// EvaluateAttention) at IoU >= `match_iou`, as the CLEAR MOT procedure does it (Bernardin and
// Stiefelhagen, "Evaluating Multiple Object Tracking Performance: The CLEAR MOT Metrics", 2008):
// the previous frame's pairs that still reach the threshold are kept, the rest are assigned by
// MinimumCostAssignment on 1 - IoU (most pairs first, then the least summed cost). A target left
// unmatched that overlaps an object present but not counted (mostly hidden or small) at the
// threshold is `ignored`: neither a false positive nor part of the identity measures, as the
// MOTChallenge devkit leaves out boxes on the objects it does not score.
//   GT    ground-truth boxes counted, over the run's frames
//   FN    of those, boxes without a target;  FP  target boxes without an object (not ignored)
//   IDSW  matches of an object to another target id than at its previous match (any frame back)
//   MOTA  1 - (FN + FP + IDSW) / GT;  MOTP  mean IoU of the matched pairs (a fraction; the
//         devkit prints the same as an overlap in percent)
//   MT, PT, ML  objects matched in >= `mostly_tracked`, in between, < `mostly_lost` of the
//         frames they are counted in;  Frag  times an object's matches resume after a counted
//         frame without one
// Identity (Ristani et al., "Performance Measures and a Data Set for Multi-Target, Multi-Camera
// Tracking", 2016): object trajectories (the frames an object is counted) and target
// trajectories (the frames a target is visible and not ignored) are assigned one to one,
// globally, minimising IDFP + IDFN; a pair's IDTP is the frames where both are present and
// overlap at IoU >= `match_iou`.
//   IDF1 = 2 IDTP / (2 IDTP + IDFP + IDFN), IDP = IDTP / (IDTP + IDFP), IDR = IDTP / (IDTP + IDFN)
// Attention, on the per-frame match:
//   objects_attended_whole   objects matched in at least one frame (a target was the whole
//                            object, not a part of it); attended_whole_fraction: / objects
//   ids_per_attended_object  distinct target ids matched to such an object, mean over them
//   purity                   over the targets with a match: the frames each is matched to the
//                            object it matched most, summed, / their matched frames summed
//   targets_started          distinct target ids in the run, in any state
// Every ratio is 0 when its denominator is 0.
#pragma once

#include <string>
#include <vector>

#include "eval/run_evaluation.h"
#include "io/ground_truth.h"
#include "io/frame_record.h"
#include "util/option_fields.h"

namespace attend {

struct MotOptions {
  double match_iou = 0.5;  // MOTChallenge's; attend eval also reports 0.3, its own match
  // Which objects count in a frame: the same rule and defaults as EvaluateAttention.
  double min_visible = EvaluationOptions{}.min_visible;
  double min_area = EvaluationOptions{}.min_area;
  double mostly_tracked = 0.8;  // share of an object's counted frames matched, MT at or above
  double mostly_lost = 0.2;     // ML below
  // "" when valid; otherwise names the field and the broken constraint.
  std::string Check() const;
  static const OptionFields<MotOptions>& Fields();
};

struct MotScores {
  double match_iou = 0.0;
  int frames = 0;   // records scored
  int objects = 0;  // objects counted in at least one frame
  // CLEAR MOT.
  int gt = 0;
  int matches = 0;  // GT - FN
  int false_positives = 0;
  int false_negatives = 0;
  int id_switches = 0;
  int ignored = 0;  // target boxes on objects present but not counted
  double mota = 0.0;
  double motp = 0.0;  // mean IoU of the matches
  int mostly_tracked = 0;
  int partly_tracked = 0;
  int mostly_lost = 0;
  int fragmentations = 0;
  // Identity.
  int idtp = 0;
  int idfp = 0;
  int idfn = 0;
  double idf1 = 0.0;
  double idp = 0.0;
  double idr = 0.0;
  // Attention.
  int objects_attended_whole = 0;
  double attended_whole_fraction = 0.0;
  double ids_per_attended_object = 0.0;
  double purity = 0.0;
  int targets_started = 0;
};

// The measures above. `options` must be valid (Check); a frame without ground-truth rows has
// no objects, so its targets are false positives.
MotScores EvaluateMot(const std::vector<FrameRecord>& frames, const std::vector<GtObject>& truth,
                      const MotOptions& options = {});


}  // namespace attend
