#include "semiattentive/followed_targets.h"

#include <algorithm>
#include <utility>

namespace attend {

namespace {

// How fast a target's velocity follows its latest displacement.
constexpr float kVelocityRate = 0.3f;
// How fast its remembered appearance follows what it looks like now.
constexpr float kAppearanceRate = 0.2f;

cv::Point2f Centre(const cv::Rect& box) {
  return {box.x + 0.5f * box.width, box.y + 0.5f * box.height};
}

}  // namespace

void FollowedTarget::Kept(const cv::Rect& box, const ObjectAppearance& seen) {
  if (!last_box.empty()) {
    const cv::Point2f moved = Centre(box) - Centre(last_box);
    const float steps = static_cast<float>(since_kept);
    velocity += kVelocityRate * (moved / steps - velocity);
  }
  last_box = box;
  since_kept = 0;
  appearance.Blend(seen, kAppearanceRate);
}

void FollowedTarget::Resume(ObjectFile file) {
  id = file.id;
  label = std::move(file.label);
  velocity = file.velocity;
  file.appearance.Blend(appearance, kAppearanceRate);
  appearance = std::move(file.appearance);
}

ObjectFile FollowedTarget::File() const {
  ObjectFile file;
  file.id = id;
  file.box = last_box;
  file.velocity = velocity;
  file.absent = since_kept;
  file.appearance = appearance;
  file.skin = skin;
  file.label = label;
  return file;
}

const FollowedTarget* FollowedTargets::OfTracker(int tracker_id) const {
  const auto found = std::find_if(targets_.begin(), targets_.end(), [&](const FollowedTarget& t) {
    return t.tracker_id == tracker_id;
  });
  return found != targets_.end() ? &*found : nullptr;
}

FollowedTarget* FollowedTargets::OfTracker(int tracker_id) {
  return const_cast<FollowedTarget*>(std::as_const(*this).OfTracker(tracker_id));
}

FollowedTarget* FollowedTargets::WithId(int id) {
  const auto found = std::find_if(targets_.begin(), targets_.end(),
                                  [&](const FollowedTarget& t) { return t.id == id; });
  return found != targets_.end() ? &*found : nullptr;
}

int FollowedTargets::Add(FollowedTarget target) {
  if (target.id == 0) target.id = next_id_++;
  targets_.push_back(std::move(target));
  return targets_.back().id;
}

void FollowedTargets::RemoveTrackers(const std::vector<int>& tracker_ids) {
  for (const int id : tracker_ids) {
    targets_.erase(std::remove_if(targets_.begin(), targets_.end(),
                                  [id](const FollowedTarget& t) { return t.tracker_id == id; }),
                   targets_.end());
  }
}

}  // namespace attend
