// What `attend run` records for each frame (SPEC 3.3, RUN/frames.jsonl).
#pragma once

#include <opencv2/core.hpp>
#include <limits>
#include <string>
#include <vector>

#include "io/target_state.h"
#include "util/timer.h"

namespace attend {

// One attended object in one frame. The pipeline fills it in working pixels (the size it
// computes at); RUN/frames.jsonl holds it in input pixels (SPEC 3.3, InputFromWorking).
struct TargetRecord {
  int id = 0;
  cv::Rect bbox;
  int area = 0;           // pixels of its mask
  double saliency = 0.0;  // mean uninhibited saliency over its mask
  TargetState state = TargetState::kNew;
  std::string kind = "object";  // object or skin
  // The tracker's similarity policy: hsv or skin (tracker kind bip); appearance for the kinds
  // that learn their own model (kcf, csrt).
  std::string similarity = "hsv";
  std::string tracker = "bip";  // the tracker kind that follows it: bip, kcf or csrt
  ReleaseReason reason = ReleaseReason::kNone;  // why it was released (state released only)
  // State resumed only: the frames its object file was remembered without being seen.
  int absent_frames = 0;
  // What a top-down channel recognised it as ("person", "face"), "" when none did.
  std::string label;
  // A stereo run (depth.method set), a target seen this frame: its disparity and standard
  // deviation (NaN when none); with a calibration, its position in the left camera's frame
  // (X right, Y down, Z forward), metres, and each coordinate's standard deviation.
  double disparity_px = std::numeric_limits<double>::quiet_NaN();
  double disparity_sd_px = std::numeric_limits<double>::quiet_NaN();
  bool has_position = false;
  // A stereo run, a target seen this frame without a disparity: why ("unmeasured": fewer than
  // depth.min_measured of its pixels have a measured disparity); "" otherwise.
  std::string depth_missing;
  cv::Vec3d position_m;
  cv::Vec3d position_sd_m;
};

struct FrameRecord {
  int frame = 0;  // index of the frame in its sequence
  std::vector<TargetRecord> targets;
  std::vector<int> new_ids;  // targets first attended in this frame
  // Share of the image inhibited in this frame (the inhibition map's mean), 0..1; -1 unknown.
  double inhibited_fraction = -1.0;
  StageTimes timings;
  // Live sources: from the frame's capture (it came out of the source's read) to this record
  // being written, ms; -1 for files, whose records do not have it.
  double latency_ms = -1.0;
};

// A box of the working frame in the pixels of the input frame, `input_size` being the input
// frame's size and scale_x, scale_y = working / input per axis (SequenceInfo::scale_x): each
// edge is divided by its scale and rounded to the nearest pixel, then clipped to the input
// frame. A non-empty box stays at least 1 px wide and high.
cv::Rect InputFromWorkingBox(const cv::Rect& box_in_working, double scale_x, double scale_y,
                             cv::Size input_size);

// The record with every box and area in input pixels: boxes by InputFromWorkingBox, areas
// divided by scale_x * scale_y and rounded (at least 1 for a non-empty mask).
FrameRecord InputFromWorking(const FrameRecord& record_in_working, double scale_x, double scale_y,
                             cv::Size input_size);

// The targets seen in the frame (Visible: new or tracked).
int VisibleTargets(const FrameRecord& record);

// One line of frames.jsonl (no trailing newline).
std::string FrameRecordToJson(const FrameRecord& record);

// Reads RUN/frames.jsonl (InputError naming the file and line of a malformed record).
std::vector<FrameRecord> ReadFrameRecords(const std::string& path);

}  // namespace attend
