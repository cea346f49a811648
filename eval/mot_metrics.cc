#include "eval/mot_metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <utility>

#include "util/assignment.h"
#include "util/box.h"
#include "util/error.h"

namespace attend {

namespace {

double Ratio(double numerator, double denominator) {
  return denominator > 0.0 ? numerator / denominator : 0.0;
}

// What one object accumulates over the run.
struct ObjectTally {
  int counted_frames = 0;
  int matched_frames = 0;
  int streaks = 0;            // runs of matched frames among its counted frames
  bool matched_last = false;  // at its last counted frame
  std::set<int> target_ids;   // matched to it
  int last_target = -1;       // at its last match
};

}  // namespace

const OptionFields<MotOptions>& MotOptions::Fields() {
  using O = MotOptions;
  static const OptionFields<MotOptions> fields = {
      {"match_iou", &O::match_iou, Range::AboveUpTo(0, 1), "a target matches an object at this IoU"},
      {"min_visible", &O::min_visible, Range::Closed(0, 1),
       "an object counts in a frame when at least this share of it is visible"},
      {"min_area", &O::min_area, Range::AtLeast(0), "... and its box holds at least this, px"},
      {"mostly_tracked", &O::mostly_tracked, Range::Closed(0, 1),
       "share of an object's frames matched at or above which it is mostly tracked"},
      {"mostly_lost", &O::mostly_lost, Range::Closed(0, 1), "... below which mostly lost"}};
  return fields;
}

std::string MotOptions::Check() const {
  const std::string error = CheckFieldRanges(*this, Fields());
  if (!error.empty()) return error;
  if (mostly_lost > mostly_tracked) return "mostly_lost must be <= mostly_tracked";
  return "";
}

namespace {

// What the frames of a run accumulate for the measures.
struct MotTally {
  std::map<int, ObjectTally> objects;                  // by object id
  std::map<int, std::map<int, int>> frames_on_object;  // target id -> object id -> frames
  std::map<int, int> target_frames;                    // target id -> frames scored
  std::map<std::pair<int, int>, int> overlap_frames;   // (object, target) -> IDTP if paired
  std::set<int> started;
  std::map<int, int> previous;  // object id -> target id, last frame
  double iou_sum = 0.0;
};

// One frame's objects, counted or present but not counted, and its visible targets.
struct FrameBoxes {
  std::vector<const GtObject*> counted, uncounted;
  std::vector<const TargetRecord*> targets;
  std::vector<cv::Rect2d> object_boxes, target_boxes;  // of counted and targets
};

FrameBoxes BoxesOf(const FrameRecord& record, const std::vector<const GtObject*>& present,
                   const MotOptions& options, MotTally* tally) {
  FrameBoxes f;
  std::set<int> seen_objects;
  for (const GtObject* object : present) {
    if (!seen_objects.insert(object->id).second) continue;  // one box an object a frame
    const bool visible =
        object->visible_fraction >= options.min_visible && object->box.area() >= options.min_area;
    (visible ? f.counted : f.uncounted).push_back(object);
  }
  std::set<int> seen_targets;
  for (const TargetRecord& target : record.targets) {
    tally->started.insert(target.id);
    if (Visible(target.state) && seen_targets.insert(target.id).second) {
      f.targets.push_back(&target);
    }
  }
  for (const GtObject* object : f.counted) f.object_boxes.push_back(object->box);
  for (const TargetRecord* target : f.targets) f.target_boxes.emplace_back(target->bbox);
  return f;
}

// The frame's pairs (object index, target index): the previous frame's pairs that still reach
// the threshold, then the rest by assignment. Marks the objects and targets used.
std::vector<std::pair<int, int>> PairFrame(const FrameBoxes& f, const MotOptions& options,
                                           const std::map<int, int>& previous,
                                           std::vector<bool>* object_used,
                                           std::vector<bool>* target_used) {
  std::vector<std::pair<int, int>> pairs;
  object_used->assign(f.counted.size(), false);
  target_used->assign(f.targets.size(), false);
  for (std::size_t i = 0; i < f.counted.size(); ++i) {
    const auto kept = previous.find(f.counted[i]->id);
    if (kept == previous.end()) continue;
    for (std::size_t j = 0; j < f.targets.size(); ++j) {
      if (f.targets[j]->id != kept->second) continue;
      if (BoxIou(f.object_boxes[i], f.target_boxes[j]) >= options.match_iou) {
        pairs.emplace_back(static_cast<int>(i), static_cast<int>(j));
        (*object_used)[i] = (*target_used)[j] = true;
      }
    }
  }
  std::vector<int> free_objects, free_targets;
  std::vector<cv::Rect2d> free_object_boxes, free_target_boxes;
  for (std::size_t i = 0; i < f.counted.size(); ++i) {
    if ((*object_used)[i]) continue;
    free_objects.push_back(static_cast<int>(i));
    free_object_boxes.push_back(f.object_boxes[i]);
  }
  for (std::size_t j = 0; j < f.targets.size(); ++j) {
    if ((*target_used)[j]) continue;
    free_targets.push_back(static_cast<int>(j));
    free_target_boxes.push_back(f.target_boxes[j]);
  }
  for (const auto& [i, j] : MatchBoxes(free_object_boxes, free_target_boxes, options.match_iou)) {
    pairs.emplace_back(free_objects[i], free_targets[j]);
    (*object_used)[free_objects[i]] = (*target_used)[free_targets[j]] = true;
  }
  return pairs;
}

// Scores one frame into `tally` and `scores`.
void ScoreFrame(const FrameRecord& record, const std::vector<const GtObject*>& present,
                const MotOptions& options, MotTally* tally, MotScores* scores) {
  const FrameBoxes f = BoxesOf(record, present, options, tally);
  scores->gt += static_cast<int>(f.counted.size());
  std::vector<bool> object_used, target_used;
  const std::vector<std::pair<int, int>> pairs =
      PairFrame(f, options, tally->previous, &object_used, &target_used);

  std::map<int, int> current;
  for (const auto& [i, j] : pairs) {
    const int object_id = f.counted[i]->id;
    const int target_id = f.targets[j]->id;
    ++scores->matches;
    tally->iou_sum += BoxIou(f.object_boxes[i], f.target_boxes[j]);
    ObjectTally& object = tally->objects[object_id];
    if (object.last_target >= 0 && object.last_target != target_id) ++scores->id_switches;
    object.last_target = target_id;
    object.target_ids.insert(target_id);
    ++tally->frames_on_object[target_id][object_id];
    current[object_id] = target_id;
  }
  tally->previous = std::move(current);
  for (std::size_t i = 0; i < f.counted.size(); ++i) {
    ObjectTally& object = tally->objects[f.counted[i]->id];
    ++object.counted_frames;
    if (object_used[i]) {
      ++object.matched_frames;
      if (!object.matched_last) ++object.streaks;
    }
    object.matched_last = object_used[i];
  }
  scores->false_negatives += static_cast<int>(f.counted.size() - pairs.size());

  // Unmatched targets on an object that is present but not counted are left out.
  std::vector<int> unmatched;
  std::vector<cv::Rect2d> unmatched_boxes, uncounted_boxes;
  for (std::size_t j = 0; j < f.targets.size(); ++j) {
    if (target_used[j]) continue;
    unmatched.push_back(static_cast<int>(j));
    unmatched_boxes.push_back(f.target_boxes[j]);
  }
  for (const GtObject* object : f.uncounted) uncounted_boxes.push_back(object->box);
  std::vector<bool> ignored(f.targets.size(), false);
  int ignored_here = 0;
  for (const std::pair<int, int>& pair :
       MatchBoxes(unmatched_boxes, uncounted_boxes, options.match_iou)) {
    ignored[unmatched[pair.first]] = true;
    ++ignored_here;
  }
  scores->ignored += ignored_here;
  scores->false_positives += static_cast<int>(unmatched.size()) - ignored_here;

  // The trajectories of the identity measures, and every overlap a pairing of them would
  // count.
  for (std::size_t j = 0; j < f.targets.size(); ++j) {
    if (ignored[j]) continue;
    ++tally->target_frames[f.targets[j]->id];
    for (std::size_t i = 0; i < f.counted.size(); ++i) {
      if (BoxIou(f.object_boxes[i], f.target_boxes[j]) >= options.match_iou) {
        ++tally->overlap_frames[{f.counted[i]->id, f.targets[j]->id}];
      }
    }
  }
}

// CLEAR MOT and the attention measures, per object.
void ScoreObjects(const MotTally& tally, const MotOptions& options, MotScores* scores) {
  int ids_matched = 0;
  for (const auto& [id, object] : tally.objects) {
    ++scores->objects;
    const double tracked = Ratio(object.matched_frames, object.counted_frames);
    if (tracked >= options.mostly_tracked) {
      ++scores->mostly_tracked;
    } else if (tracked < options.mostly_lost) {
      ++scores->mostly_lost;
    } else {
      ++scores->partly_tracked;
    }
    if (object.streaks > 1) scores->fragmentations += object.streaks - 1;
    if (object.matched_frames > 0) {
      ++scores->objects_attended_whole;
      ids_matched += static_cast<int>(object.target_ids.size());
    }
  }
  scores->mota = scores->gt > 0
                     ? 1.0 - static_cast<double>(scores->false_negatives +
                                                 scores->false_positives + scores->id_switches) /
                                 scores->gt
                     : 0.0;
  scores->motp = Ratio(tally.iou_sum, scores->matches);
  scores->attended_whole_fraction = Ratio(scores->objects_attended_whole, scores->objects);
  scores->ids_per_attended_object = Ratio(ids_matched, scores->objects_attended_whole);
  int purest = 0;
  for (const auto& [target, on] : tally.frames_on_object) {
    int most = 0;
    for (const auto& [object, count] : on) most = std::max(most, count);
    purest += most;
  }
  scores->purity = Ratio(purest, scores->matches);
  scores->targets_started = static_cast<int>(tally.started.size());
}

// The IDTP of the identity assignment within one group of objects and targets (rows 0..G-1
// objects, columns 0..T-1 targets) padded so that either may go unpaired. Object i with target
// j costs its IDFN + IDFP, (n_i - tp) + (n_j - tp); object i unpaired (column T + i) costs n_i,
// target j unpaired (row G + j) n_j, two paddings 0; any other padding cell more than the whole
// of either trajectory set.
int GroupIdtp(const MotTally& tally, const std::vector<int>& object_ids,
              const std::vector<int>& object_length, const std::vector<int>& target_ids,
              const std::vector<int>& target_length, double forbidden) {
  const int g = static_cast<int>(object_ids.size());
  const int t = static_cast<int>(target_ids.size());
  std::vector<std::vector<double>> cost(g + t, std::vector<double>(t + g, forbidden));
  for (int i = 0; i < g; ++i) {
    for (int j = 0; j < t; ++j) {
      const auto overlap = tally.overlap_frames.find({object_ids[i], target_ids[j]});
      const int tp = overlap != tally.overlap_frames.end() ? overlap->second : 0;
      cost[i][j] = object_length[i] + target_length[j] - 2.0 * tp;
    }
    cost[i][t + i] = object_length[i];
  }
  for (int j = 0; j < t; ++j) {
    cost[g + j][j] = target_length[j];
    for (int i = 0; i < g; ++i) cost[g + j][t + i] = 0.0;
  }
  const std::vector<int> column = MinimumCostAssignment(cost);
  int idtp = 0;
  for (int i = 0; i < g; ++i) {
    if (column[i] >= t) continue;
    const auto overlap = tally.overlap_frames.find({object_ids[i], target_ids[column[i]]});
    if (overlap != tally.overlap_frames.end()) idtp += overlap->second;
  }
  return idtp;
}

// Objects and targets in one group of the identity assignment, at most: its cost matrix holds
// (G + T)^2 numbers and the solver takes O((G + T)^3) steps (4000: 128 MB, about a minute).
constexpr int kMaxIdentityGroup = 4000;

// Identity (IDF1): the assignment of objects to targets that maximises IDTP. An object and a
// target that never overlap gain nothing from being paired, so the assignment splits into the
// connected groups of the graph of overlapping (object, target) pairs, solved one by one: the
// same optimum as one matrix of every object and target, whose size grew with the square of
// all the ids of a sequence (issue 46: 300,000 objects took 24 GB before it was killed).
void ScoreIdentity(const MotTally& tally, MotScores* scores) {
  int target_detections = 0;
  for (const auto& [id, count] : tally.target_frames) target_detections += count;
  const double forbidden = static_cast<double>(scores->gt + target_detections) + 1.0;
  // Union-find over objects (keys o) and targets (keys t), joined by their overlaps.
  std::map<std::pair<char, int>, std::pair<char, int>> parent;
  const auto root = [&](std::pair<char, int> node) {
    auto it = parent.find(node);
    if (it == parent.end()) return parent[node] = node;
    std::pair<char, int> top = node;
    while (parent.at(top) != top) top = parent.at(top);
    while (node != top) {  // path compression, without recursion: chains can be long
      std::pair<char, int>& up = parent.at(node);
      node = std::exchange(up, top);
    }
    return top;
  };
  for (const auto& [pair, frames] : tally.overlap_frames) {
    if (frames <= 0) continue;
    const auto a = root({'o', pair.first}), b = root({'t', pair.second});
    if (a != b) parent[a] = b;
  }
  std::map<std::pair<char, int>, std::vector<std::pair<char, int>>> groups;
  for (const auto& [node, up] : parent) groups[root(node)].push_back(node);
  for (const auto& [group_root, members] : groups) {
    if (members.size() > static_cast<size_t>(kMaxIdentityGroup)) {
      throw InputError("IDF1: " + std::to_string(members.size()) + " objects and targets overlap " +
                       "one another in one chain, more than the " +
                       std::to_string(kMaxIdentityGroup) + " the identity assignment takes " +
                       "(docs/LIMITS.md)");
    }
    std::vector<int> object_ids, object_length, target_ids, target_length;
    for (const auto& [kind, id] : members) {
      if (kind == 'o') {
        object_ids.push_back(id);
        const auto object = tally.objects.find(id);
        object_length.push_back(object != tally.objects.end() ? object->second.counted_frames : 0);
      } else {
        target_ids.push_back(id);
        const auto target = tally.target_frames.find(id);
        target_length.push_back(target != tally.target_frames.end() ? target->second : 0);
      }
    }
    scores->idtp +=
        GroupIdtp(tally, object_ids, object_length, target_ids, target_length, forbidden);
  }
  scores->idfn = scores->gt - scores->idtp;
  scores->idfp = target_detections - scores->idtp;
  scores->idf1 = Ratio(2.0 * scores->idtp, 2.0 * scores->idtp + scores->idfp + scores->idfn);
  scores->idp = Ratio(scores->idtp, scores->idtp + scores->idfp);
  scores->idr = Ratio(scores->idtp, scores->idtp + scores->idfn);
}

}  // namespace

MotScores EvaluateMot(const std::vector<FrameRecord>& frames, const std::vector<GtObject>& truth,
                      const MotOptions& options) {
  const std::string error = options.Check();
  ATTEND_CHECK(error.empty()) << error;
  std::map<int, std::vector<const GtObject*>> by_frame;
  for (const GtObject& object : truth) by_frame[object.frame].push_back(&object);
  MotScores scores;
  scores.match_iou = options.match_iou;
  scores.frames = static_cast<int>(frames.size());
  MotTally tally;
  const std::vector<const GtObject*> no_objects;
  for (const FrameRecord& record : frames) {
    const auto found = by_frame.find(record.frame);
    ScoreFrame(record, found != by_frame.end() ? found->second : no_objects, options, &tally,
               &scores);
  }
  ScoreObjects(tally, options, &scores);
  ScoreIdentity(tally, &scores);
  return scores;
}

}  // namespace attend
