// The BIP tracker's correlation mode (tracker.mode correlation; docs/TRACKING.md, "The
// correlation mode"): a tracker for real footage that learns its target against the
// background around it.
//
// Per target and frame: a window around the target (its box grown by `padding`), resampled to
// a fixed area, is described by cells of oriented gradients (tracker/hog_features.h); a
// discriminative correlation filter learnt on the earlier frames responds over it (DSST's
// translation filter, tracker/correlation_filter.h), and so does a colour model learnt against
// the window's surroundings (Staple's, tracker/colour_likelihood.h); the peak of their weighted
// sum is the target's new position. A 1-D filter over samples at 33 scales then estimates its
// size on its own (DSST). The peak's height against its running mean is the tracker's
// confidence: an untrusted frame teaches nothing and is searched again over a wider window,
// and a target without a trusted frame is occluded at its last box, and lost after
// `missed_frames`. The target's mask is the BIP over-segmentation's regions of its box whose
// colours are more the target's than its surroundings'.
#pragma once

#include <memory>

#include "tracker/correlation_options.h"
#include "tracker/target_tracker.h"

namespace attend {

class BipPool;

// The tracker; `pool`: the pool of the masks' pyramids (nullptr: its own).
std::unique_ptr<TargetTracker> MakeCorrelationTracker(const CorrelationOptions& options,
                                                      BipPool* pool);

}  // namespace attend
