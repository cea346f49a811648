// What `attend run` records for each frame (SPEC 3.3, RUN/frames.jsonl).
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "util/timer.h"

namespace attend {

// One attended object in one frame.
struct TargetRecord {
  int id = 0;
  cv::Rect bbox;
  int area = 0;                    // pixels of its mask
  double saliency = 0.0;           // mean uninhibited saliency over its mask
  std::string state = "new";       // new, tracked, occluded, lost, released
  std::string kind = "object";     // object or skin
  // The tracker's similarity policy: hsv or skin (tracker kind bip); appearance for the kinds
  // that learn their own model (kcf, csrt).
  std::string similarity = "hsv";
  std::string tracker = "bip";  // the tracker kind that follows it: bip, kcf or csrt
  std::string reason;           // why it was released (state released only; else empty)
};

struct FrameRecord {
  int frame = 0;  // index of the frame in its sequence
  std::vector<TargetRecord> targets;
  std::vector<int> new_ids;  // targets first attended in this frame
  StageTimes timings;
};

// One line of frames.jsonl (no trailing newline).
std::string FrameRecordToJson(const FrameRecord& record);

}  // namespace attend
