#include "eval/run_evaluation.h"

#include <algorithm>
#include <map>
#include <set>

#include "util/box.h"

namespace attend {

namespace {

// The new targets of `record` whose best-overlapping visible object (IoU at least
// `match_iou`) another active target was already on: revisits, whether or not they won the
// object in the matching.
int CountRevisits(const FrameRecord& record, const std::vector<const GtObject*>& visible,
                  const std::set<int>& active_objects, double match_iou) {
  int revisits = 0;
  for (const TargetRecord& target : record.targets) {
    if (target.state != TargetState::kNew) continue;
    const GtObject* best = nullptr;
    double best_iou = match_iou;
    for (const GtObject* object : visible) {
      const double iou = BoxIou(cv::Rect2d(target.bbox), object->box);
      if (iou >= best_iou) best = object, best_iou = iou;
    }
    if (best != nullptr && active_objects.count(best->id) > 0) ++revisits;
  }
  return revisits;
}

// The per-object scores into the totals of `scores` (objects, attended, switches) and its
// means (coverage, latency, IoU over `scores->matches` matches summing `iou_sum`).
void TallyObjects(const std::map<int, ObjectScore>& objects, double iou_sum,
                  AttentionScores* scores) {
  double latency = 0.0;
  for (const auto& [id, score] : objects) {
    ++scores->objects;
    if (score.first_attended >= 0) {
      ++scores->attended;
      latency += std::max(0, score.first_attended - score.first_visible);
    }
    scores->identity_switches += score.switches;
    scores->per_object.push_back(score);
  }
  scores->coverage =
      scores->objects > 0 ? static_cast<double>(scores->attended) / scores->objects : 0.0;
  scores->mean_latency = scores->attended > 0 ? latency / scores->attended : 0.0;
  scores->mean_iou = scores->matches > 0 ? iou_sum / scores->matches : 0.0;
}

}  // namespace

AttentionScores EvaluateAttention(const std::vector<FrameRecord>& frames,
                                  const std::vector<GtObject>& truth,
                                  const EvaluationOptions& options) {
  // Ground truth by frame.
  std::map<int, std::vector<const GtObject*>> by_frame;
  for (const GtObject& object : truth) by_frame[object.frame].push_back(&object);

  AttentionScores scores;
  scores.frames = static_cast<int>(frames.size());
  std::map<int, ObjectScore> objects;   // by object id
  std::map<int, int> current_target;    // object id -> target id last on it
  std::map<int, int> object_of_target;  // target id -> object id it was last on
  double iou_sum = 0.0;
  for (const FrameRecord& record : frames) {
    const auto found = by_frame.find(record.frame);
    if (found == by_frame.end()) continue;
    std::vector<const GtObject*> visible;
    for (const GtObject* object : found->second) {
      if (object->visible_fraction >= options.min_visible &&
          object->box.area() >= options.min_area) {
        visible.push_back(object);
        ObjectScore& score = objects[object->id];
        score.id = object->id;
        score.kind = object->kind;
        if (score.first_visible < 0) score.first_visible = record.frame;
      }
    }
    // The targets still active (tracked or occluded) this frame, and the objects they were on.
    std::set<int> active_objects;
    for (const TargetRecord& target : record.targets) {
      if (target.state == TargetState::kTracked || target.state == TargetState::kOccluded) {
        const auto on = object_of_target.find(target.id);
        if (on != object_of_target.end()) active_objects.insert(on->second);
      }
    }
    // One-to-one matching, greedy by IoU: every visible target with every visible object.
    struct Pair {
      double iou;
      const TargetRecord* target;
      const GtObject* object;
    };
    std::vector<Pair> pairs;
    for (const TargetRecord& target : record.targets) {
      if (!Visible(target.state)) continue;
      for (const GtObject* object : visible) {
        const double iou = BoxIou(cv::Rect2d(target.bbox), object->box);
        if (iou >= options.match_iou) pairs.push_back({iou, &target, object});
      }
    }
    std::stable_sort(pairs.begin(), pairs.end(),
                     [](const Pair& a, const Pair& b) { return a.iou > b.iou; });
    std::set<int> used_targets, used_objects;
    for (const Pair& pair : pairs) {
      const TargetRecord& target = *pair.target;
      const GtObject* best = pair.object;
      if (used_targets.count(target.id) > 0 || used_objects.count(best->id) > 0) continue;
      used_targets.insert(target.id);
      used_objects.insert(best->id);
      ++scores.matches;
      iou_sum += pair.iou;
      ObjectScore& score = objects[best->id];
      if (score.first_attended < 0) score.first_attended = record.frame;
      const auto previous = current_target.find(best->id);
      if (previous != current_target.end() && previous->second != target.id) ++score.switches;
      current_target[best->id] = target.id;
      object_of_target[target.id] = best->id;
    }
    scores.revisits += CountRevisits(record, visible, active_objects, options.match_iou);
  }
  TallyObjects(objects, iou_sum, &scores);
  return scores;
}

}  // namespace attend
