// The rows of the tracker kinds (TrackerKindInfo), each defined in its kind's file beside its
// class; TrackerKinds() (target_tracker.cc) lists them. Not part of the public API.
#pragma once

#include "tracker/target_tracker.h"

namespace attend {

const TrackerKindInfo& BipKind();   // bip_target_tracker.cc
const TrackerKindInfo& KcfKind();   // opencv_target_tracker.cc
const TrackerKindInfo& CsrtKind();  // opencv_target_tracker.cc

}  // namespace attend
