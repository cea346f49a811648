#include "semiattentive/target_state.h"

#include <array>
#include <utility>

namespace attend {

namespace {

constexpr std::array<std::pair<TargetState, const char*>, 6> kStateNames = {{
    {TargetState::kNew, "new"},
    {TargetState::kTracked, "tracked"},
    {TargetState::kOccluded, "occluded"},
    {TargetState::kLost, "lost"},
    {TargetState::kReleased, "released"},
    {TargetState::kResumed, "resumed"},
}};

constexpr std::array<std::pair<ReleaseReason, const char*>, 7> kReasonNames = {{
    {ReleaseReason::kNone, ""},
    {ReleaseReason::kTooLarge, "too_large"},
    {ReleaseReason::kSpansImage, "spans_image"},
    {ReleaseReason::kTooSmall, "too_small"},
    {ReleaseReason::kLowSaliency, "low_saliency"},
    {ReleaseReason::kDuplicate, "duplicate"},
    {ReleaseReason::kUnrecognised, "unrecognised"},
}};

template <typename Enum, size_t N>
const char* NameOf(const std::array<std::pair<Enum, const char*>, N>& names, Enum value) {
  for (const auto& [entry, name] : names) {
    if (entry == value) return name;
  }
  return "?";
}

template <typename Enum, size_t N>
bool ValueOf(const std::array<std::pair<Enum, const char*>, N>& names, const std::string& name,
             Enum* value) {
  for (const auto& [entry, entry_name] : names) {
    if (name == entry_name) {
      *value = entry;
      return true;
    }
  }
  return false;
}

}  // namespace

const char* TargetStateName(TargetState state) { return NameOf(kStateNames, state); }

bool TargetStateFromName(const std::string& name, TargetState* state) {
  return ValueOf(kStateNames, name, state);
}

const char* ReleaseReasonName(ReleaseReason reason) { return NameOf(kReasonNames, reason); }

}  // namespace attend
