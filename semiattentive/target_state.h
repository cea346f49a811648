// The state of an attended target in a frame, and why a released target was released
// (SPEC 3.3). The program works with the enums; the strings are SPEC's, written and read only
// where records leave or enter the program (frames.jsonl, overlays, reports).
#pragma once

#include <ostream>
#include <string>

namespace attend {

// new (the frame it starts) -> tracked (found) / occluded (not found) -> lost; or released.
enum class TargetState { kNew, kTracked, kOccluded, kLost, kReleased };

// Why a found target was released (semiattentive/attention.h); kNone in every other state.
enum class ReleaseReason { kNone, kTooLarge, kSpansImage, kTooSmall, kLowSaliency, kDuplicate };

// "new", "tracked", "occluded", "lost", "released".
const char* TargetStateName(TargetState state);
// The state called `name`; false when there is none.
bool TargetStateFromName(const std::string& name, TargetState* state);
// "" (kNone), "too_large", "spans_image", "too_small", "low_saliency", "duplicate".
const char* ReleaseReasonName(ReleaseReason reason);
// The reason called `name` ("" is kNone); false when there is none.
bool ReleaseReasonFromName(const std::string& name, ReleaseReason* reason);

// Whether a target in this state was seen in its frame (new or tracked): it has a box there
// and counts as attended, for overlays, evaluation and comparison.
inline bool Visible(TargetState state) {
  return state == TargetState::kNew || state == TargetState::kTracked;
}

// For test messages and logs: the names above.
inline std::ostream& operator<<(std::ostream& out, TargetState state) {
  return out << TargetStateName(state);
}
inline std::ostream& operator<<(std::ostream& out, ReleaseReason reason) {
  return out << ReleaseReasonName(reason);
}

}  // namespace attend
