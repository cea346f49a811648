// The scene truth of a sequence rendered by `attend synth` from a street scene (docs/SYNTH.md,
// "Street scenes"; eval/scene_truth.h), for the landing scores of eval/landing.h.
#pragma once

#include <string>

#include "eval/scene_truth.h"

namespace attend {

// Truth points are taken on a regular grid of this step (pixels, from (0, 0)): a quarter of the
// pixels, enough to fill a box's inner half many times and four times lighter.
inline constexpr int kRenderedPointStep = 2;

// Whether `gt_folder` holds rendered per-pixel truth (a classes/ folder).
bool HasRenderedTruth(const std::string& gt_folder);

// Reads SEQ/gt of a rendered street scene into a SceneTruth, one FrameTruth per map of
// gt/classes/NNNNNN.png:
//   objects  the rows of gt/objects.csv of that frame with a non-empty visible box; depth_m
//            f B / disparity from the row's disparity;
//   points   the grid pixels (step kRenderedPointStep) whose gt/disparity/NNNNNN.pfm value is
//            > 0 (the sky's 0 is unknown: no point), depth_m = focal_px * baseline_m /
//            disparity from SEQ/sequence.yaml; ground when the pixel's class is 2 (ground);
//   horizon  gt/horizon.txt ("a b c" of a u + b v + c = 0, after '#' comment lines); no valid
//            horizon when the file is absent.
// InputError naming the file for a missing disparity map, maps of different sizes, a class
// outside 0..4, a malformed horizon or objects.csv, or a sequence.yaml without focal_px and
// baseline_m.
SceneTruth ReadRenderedTruth(const std::string& sequence_folder);

}  // namespace attend
