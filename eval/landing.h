// Where attention lands (issue 55; docs/ATTENTION.md, "Where attention lands"): the share of a
// run's target-frames on labelled objects, on the sky, on the ground or without depth, how soon
// each object is attended, and how far the targets' depths are from the truth, against a
// SceneTruth (eval/scene_truth.h) from a rendered street scene or a KITTI drive.
//
// Definitions (boxes in input pixels; a point is inside a box when x <= u < x + w and
// y <= v < y + h):
//   - A target-frame is a target seen in a frame: state new, tracked or resumed (Visible,
//     io/target_state.h). Its box is the FrameRecord target's bbox.
//   - The inner half of a box: the box of half its width and half its height about the same
//     centre.
//   - on_object: the box has at least half its area inside some labelled object's box of the
//     frame (intersection area / target box area >= 0.5), or IoU >= 0.3 with it. It is paired
//     with the qualifying object of the largest intersection / target area.
//   - on_sky (the sky, or above the depth sensor's view): no truth point in the inner half, and
//     the box centre above the horizon (v < HorizonV(u)); without a valid horizon only the
//     first condition.
//   - on_ground: the inner half holds truth points and at least 0.7 of them are ground points.
//     A LiDAR point is a ground point within 0.3 m of the frame's ground plane, a rendered one
//     when its class is ground: the inner half is used for both.
//   - without_depth: no truth point in the inner half (whatever the horizon).
//   - The categories are counted independently (a target-frame on an object may be on the
//     ground too); elsewhere: neither on_object, on_sky nor on_ground.
//   - Shares: each count over all target-frames. object_share_in_view: over the frames whose
//     truth has at least one labelled object, the target-frames on objects over the
//     target-frames of those frames.
//   - Per labelled object: the first frame it is in the truth (among the frames scored), the
//     first frame a target-frame is on it (paired as above), the frames between (none when
//     never attended); attended_within: the objects attended within `attended_window` frames
//     of their first visible frame.
//   - Depth: for each target-frame with a position and at least 3 truth points in its inner
//     half, the truth depth is the median depth_m of those points and the error |Z - truth| /
//     truth, Z the target's position_m[2].
//   - Frames of the run without a truth frame are skipped (frames_without_truth).
#pragma once

#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "eval/scene_truth.h"
#include "io/frame_record.h"

namespace attend {

struct LandingOptions {
  double object_cover = 0.5;  // intersection / target box area for on_object
  double object_iou = 0.3;    // or this IoU
  double ground_share = 0.7;  // of the inner half's points, for on_ground
  int attended_window = 10;   // frames, for attended_within
  int depth_points = 3;       // truth points needed in the inner half for a depth
  double depth_within = 0.1;  // relative error counted as within
};

// One labelled object of the truth.
struct LandingObject {
  int id = 0;
  std::string kind;
  int first_visible = 0;
  std::optional<int> first_attended;  // none when never attended
  // first_attended - first_visible; none when never attended.
  std::optional<int> frames_to_attend;
};

struct LandingScores {
  LandingOptions options;
  int frames = 0;                // frames of the run scored (with a truth frame)
  int frames_without_truth = 0;  // frames of the run skipped
  int target_frames = 0;
  int on_object = 0, on_sky = 0, on_ground = 0, without_depth = 0, elsewhere = 0;
  int frames_with_objects = 0;         // scored frames whose truth has a labelled object
  int target_frames_with_objects = 0;  // target-frames of those frames
  int on_object_with_objects = 0;      // of those, on an object
  std::vector<LandingObject> objects;  // by id
  int attended_within = 0;             // objects attended within options.attended_window
  // Depth of the targets against the truth points.
  int depth_target_frames = 0;
  double depth_share_within = std::numeric_limits<double>::quiet_NaN();
  double median_relative_depth_error = std::numeric_limits<double>::quiet_NaN();
  double median_abs_depth_error_m = std::numeric_limits<double>::quiet_NaN();

  // count / target_frames (NaN without target-frames).
  double Share(int count) const;
  // on_object_with_objects / target_frames_with_objects (NaN without).
  double ObjectShareInView() const;
};

LandingScores EvaluateLanding(const std::vector<FrameRecord>& frames, const SceneTruth& truth,
                              const LandingOptions& options = {});

// The "landing" block of attend eval (docs/ATTENTION.md): counts, shares, per-object latency
// and depth; NaN and unknown values as null.
nlohmann::ordered_json LandingToJson(const LandingScores& scores);

}  // namespace attend
