// The state of an attended target in a frame, and why a released target was released
// (SPEC 3.3). The program works with the enums; the strings are SPEC's, written and read only
// where records leave or enter the program (frames.jsonl, overlays, reports).
#pragma once

#include <ostream>
#include <string>

namespace attend {

// new (the frame it starts) -> tracked (found) / occluded (not found) -> lost; or released.
// resumed: the frame a remembered object (an object file, semiattentive/object_files.h) is
// attended again under its old id; it is tracked from the next frame on.
enum class TargetState { kNew, kTracked, kOccluded, kLost, kReleased, kResumed };

// Why a found target was released (semiattentive/attention.h); kNone in every other state.
enum class ReleaseReason {
  kNone,
  kTooLarge,
  kSpansImage,
  kTooSmall,
  kLowSaliency,
  kDuplicate,
  kUnrecognised,
  kDepthJump,
  kBackground,  // its mask is mostly background (select.background)
  kDwell        // attended for attention.dwell_s: attention moves on
};

// "new", "tracked", "occluded", "lost", "released", "resumed".
const char* TargetStateName(TargetState state);
// The state called `name`; false when there is none.
bool TargetStateFromName(const std::string& name, TargetState* state);
// "" (kNone), "too_large", "spans_image", "too_small", "low_saliency", "duplicate",
// "unrecognised", "depth_jump", "background", "dwell".
const char* ReleaseReasonName(ReleaseReason reason);

// Whether a target in this state was seen in its frame (new, tracked or resumed): it has a box
// there and counts as attended, for overlays, evaluation and comparison.
inline bool Visible(TargetState state) {
  return state == TargetState::kNew || state == TargetState::kTracked ||
         state == TargetState::kResumed;
}

// For test messages and logs: the names above.
inline std::ostream& operator<<(std::ostream& out, TargetState state) {
  return out << TargetStateName(state);
}
inline std::ostream& operator<<(std::ostream& out, ReleaseReason reason) {
  return out << ReleaseReasonName(reason);
}

}  // namespace attend
