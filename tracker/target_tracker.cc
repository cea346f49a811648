#include "tracker/target_tracker.h"

#include <algorithm>
#include <opencv2/core.hpp>

#include "tracker/tracker_kinds.h"
#include "util/error.h"

namespace attend {

// The kinds' table. Adding a kind: CONTRIBUTING.md, "A tracker kind" (a file with its row,
// and its row function in this list).
const std::vector<TrackerKindInfo>& TrackerKinds() {
  // One row a kind, each from its kind's file (tracker_kinds.h).
  static const std::vector<TrackerKindInfo> kinds = {BipKind(), KcfKind(), CsrtKind()};
  return kinds;
}

const TrackerKindInfo& TrackerKindOf(TrackerKind kind) {
  for (const TrackerKindInfo& info : TrackerKinds()) {
    if (info.kind == kind) return info;
  }
  ATTEND_CHECK(false) << "a tracker kind without a row in TrackerKinds()";
  return TrackerKinds().front();
}

const char* TrackerKindName(TrackerKind kind) { return TrackerKindOf(kind).name; }

const std::vector<std::string>& TrackerKindNames() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> result;
    for (const TrackerKindInfo& info : TrackerKinds()) result.emplace_back(info.name);
    return result;
  }();
  return names;
}

bool TrackerKindFromName(std::string_view name, TrackerKind* kind) {
  for (const TrackerKindInfo& info : TrackerKinds()) {
    if (name == info.name) {
      *kind = info.kind;
      return true;
    }
  }
  return false;
}

const OptionFields<OpenCvTrackerOptions>& OpenCvTrackerOptions::Fields() {
  using O = OpenCvTrackerOptions;
  static const OptionFields<OpenCvTrackerOptions> fields = {
      {"lost_frames", &O::lost_frames, Range::Closed(1, 1e6),
       "kcf, csrt: a target whose tracker fails this many frames in a row is lost"},
      {"kcf_detect_thresh", &O::kcf_detect_thresh, Range::Closed(0, 1),
       "kcf: the peak response below which KCF reports failure"}};
  return fields;
}

std::string OpenCvTrackerOptions::Check() const { return CheckFieldRanges(*this, Fields()); }

const OptionFields<TargetTrackerOptions>& TargetTrackerOptions::Fields() {
  using O = TargetTrackerOptions;
  static const OptionFields<TargetTrackerOptions> fields = {
      {"kind",
       EnumMember<O>{
           [](const O& o) { return std::string(TrackerKindName(o.kind)); },
           [](O* o, std::string_view name) { return TrackerKindFromName(name, &o->kind); },
           &TrackerKindNames, [](const O& o) -> const void* { return &o.kind; }},
       "the tracker: bip (the thesis's, chapter 4), or OpenCV's kcf or csrt"}};
  return fields;
}

std::string TargetTrackerOptions::Check() const { return TrackerKindOf(kind).check(*this); }

int TargetTracker::StartFromRegion(const cv::Mat& frame, const cv::Mat& labels, int region,
                                   TrackSimilarity similarity, const cv::Mat& skin) {
  ATTEND_CHECK(labels.type() == CV_32SC1 && labels.size() == frame.size())
      << "labels must be CV_32SC1 of the frame's size";
  const cv::Mat mask = labels == region;
  if (cv::countNonZero(mask) == 0) return -1;
  return StartFromMask(frame, mask, similarity, skin);
}

std::unique_ptr<TargetTracker> TargetTracker::Create(const TargetTrackerOptions& options,
                                                     BipPool* pool) {
  const std::string error = options.Check();
  if (!error.empty()) throw ConfigError("tracker." + error);
  return TrackerKindOf(options.kind).create(options, pool);
}

}  // namespace attend
