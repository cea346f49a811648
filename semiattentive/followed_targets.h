// The targets the attention stage follows from frame to frame: each one's ids, its counters for
// the release rules and recognition, its label, and what its object file would keep (where it
// was last found and kept, how fast it moved, what it looked like). The attention stage's one
// owner of per-target state across frames.
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "semiattentive/object_files.h"

namespace attend {

struct FollowedTarget {
  int id = 0;          // the target's id in the records
  int tracker_id = 0;  // its id in the tracker
  bool skin = false;
  int low_frames = 0;    // consecutive frames below drop.min_saliency
  int unseen = 0;        // consecutive frames not found (occluded)
  int unrecognised = 0;  // consecutive frames with detections, none on it
  int since_kept = 0;    // frames since last_box was last updated
  int since_embedding = 0;  // frames kept since its appearance's embedding was last taken
  int found_frames = 0;     // frames found since it was started or resumed (attention.dwell_s)
  int background_frames = 0;  // frames in a row found mostly on background (select.background)
  std::string label;     // from the top-down channels, once given
  // For its object file (object files or the re-anchoring's look gate only): where it was last
  // found and kept, how fast it moved, and what it looked like.
  cv::Rect last_box;
  cv::Point2f velocity;
  ObjectAppearance appearance;

  // Kept this frame at `box`, looking like `seen`: its velocity follows its displacement since
  // it was last kept, its appearance follows what it looks like now.
  void Kept(const cv::Rect& box, const ObjectAppearance& seen);
  // Starts as the object of `file` attended again: its id, its label, its motion and its
  // appearance (blended with what it looks like now).
  void Resume(ObjectFile file);
  // The file it leaves when it ends.
  ObjectFile File() const;
};

class FollowedTargets {
 public:
  // The target its tracker follows under `tracker_id`; nullptr when none.
  const FollowedTarget* OfTracker(int tracker_id) const;
  FollowedTarget* OfTracker(int tracker_id);
  // The target with record id `id`; nullptr when none.
  FollowedTarget* WithId(int id);
  // Adds `target`; a new object (id 0) is given the next id first. Returns its id.
  int Add(FollowedTarget target);
  // Removes the targets of these tracker ids.
  void RemoveTrackers(const std::vector<int>& tracker_ids);

  int size() const { return static_cast<int>(targets_.size()); }
  // New objects attended so far (resumed ones are not counted again).
  int attended() const { return next_id_ - 1; }

 private:
  std::vector<FollowedTarget> targets_;
  int next_id_ = 1;  // the id the next new target gets (the tracker's own ids are internal)
};

}  // namespace attend
