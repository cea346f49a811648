// The factories of the tracker kinds, one file each; TrackerKinds() (target_tracker.cc) lists
// them. Not part of the public API.
#pragma once

#include <memory>

#include "tracker/target_tracker.h"

namespace attend {

std::unique_ptr<TargetTracker> CreateBipTracker(const TargetTrackerOptions& options, BipPool* pool);
std::unique_ptr<TargetTracker> CreateKcfTracker(const TargetTrackerOptions& options, BipPool* pool);
std::unique_ptr<TargetTracker> CreateCsrtTracker(const TargetTrackerOptions& options,
                                                 BipPool* pool);

}  // namespace attend
