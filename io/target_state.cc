#include "io/target_state.h"

#include "util/enum_table.h"

namespace attend {

namespace {

constexpr EnumTable<TargetState, 6> kStateNames = {{{
    {TargetState::kNew, "new"},
    {TargetState::kTracked, "tracked"},
    {TargetState::kOccluded, "occluded"},
    {TargetState::kLost, "lost"},
    {TargetState::kReleased, "released"},
    {TargetState::kResumed, "resumed"},
}}};

constexpr EnumTable<ReleaseReason, 10> kReasonNames = {{{
    {ReleaseReason::kNone, ""},
    {ReleaseReason::kTooLarge, "too_large"},
    {ReleaseReason::kSpansImage, "spans_image"},
    {ReleaseReason::kTooSmall, "too_small"},
    {ReleaseReason::kLowSaliency, "low_saliency"},
    {ReleaseReason::kDuplicate, "duplicate"},
    {ReleaseReason::kUnrecognised, "unrecognised"},
    {ReleaseReason::kDepthJump, "depth_jump"},
    {ReleaseReason::kBackground, "background"},
    {ReleaseReason::kDwell, "dwell"},
}}};

}  // namespace

const char* TargetStateName(TargetState state) { return kStateNames.Name(state); }

bool TargetStateFromName(const std::string& name, TargetState* state) {
  return kStateNames.FromName(name, state);
}

const char* ReleaseReasonName(ReleaseReason reason) { return kReasonNames.Name(reason); }

}  // namespace attend
