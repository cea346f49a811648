// The controller of `attend eval` (SPEC 3.2, 4): the attention metrics of a run folder against
// the ground truth of its sequence (or another gt/ folder), the MOTChallenge measures at IoU 0.5
// and 0.3 ("mot"), the disparity scores when the run dumped its disparity maps, and where
// attention lands ("landing", eval/landing.h) when the gt/ folder holds per-pixel truth (a
// rendered street scene's classes/, read with the sequence folder around it). The command
// only parses its arguments and prints the report.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "eval/scene_truth.h"
#include "io/source_spec.h"

namespace attend {

// `gt`: a gt/ folder (objects.csv, optionally disparity/*.pfm); empty: the gt/ of the run's
// sequence folder. Returns the report attend eval prints. InputError for a folder that is not
// a run, missing ground truth or a run whose boxes are not in input pixels; ConfigError when
// no gt/ folder is given and the run's source is not a sequence folder.
// A run of a KITTI raw drive or tracking sequence (io/kitti_layout.h) is scored, when `gt` is
// empty, against the sequence's own labels (ReadKittiObjects), and its targets' depth against
// its LiDAR scans ("depth_lidar", eval/lidar_depth.h).
nlohmann::ordered_json EvaluateRunFolder(const std::string& run, const std::string& gt);

// The scene truth of the sequence `source` names (eval/scene_truth.h): a KITTI raw drive's or
// tracking sequence's (eval/kitti_truth.h); nullopt for every other source.
std::optional<SceneTruth> SequenceSceneTruth(const SourceSpec& source);

}  // namespace attend
