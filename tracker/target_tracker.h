// One interface over the trackers that can follow attended targets: the BIP template
// tracker of thesis chapter 4 (tracker/tracker.h) and OpenCV's KCF and CSRT, chosen by
// `tracker.kind` (configs/README.md; docs/TRACKING.md, "Tracker kinds").
//
//   TargetTrackerOptions options;
//   options.kind = TrackerKind::kCsrt;
//   std::unique_ptr<TargetTracker> tracker = TargetTracker::Create(options);
//   const int id = tracker->StartFromBox(frame, box);
//   tracker->Track(next_frame, &results);  // one TrackResult per target, in id order
//   const cv::Mat mask = tracker->Mask(id);
//
// Every kind reports the same things: per target and frame a state (found, occluded, lost), a
// box in the frame's pixels and a mask; ids 1, 2, ... in order of starting; a target reported
// lost is removed after that report. What differs, by kind:
//   bip   MultiTracker: one shared pyramid over the targets' regions of interest; masks are
//         the target's own pixels; a skin target (TrackSimilarity::kSkin) is matched on the
//         skin map passed with each frame; lost when its template is forgotten (1 / alpha
//         frames unseen).
//   kcf,  one cv::TrackerKCF (default Params but detect_thresh = kcf_detect_thresh) or
//   csrt  cv::TrackerCSRT (default Params) per target, on
//         the 8-bit BGR frame; the similarity and the skin map are not used (the trackers learn
//         their own appearance model). A frame in which the tracker reports failure is occluded
//         (the box stays the last one found); `lost_frames` failures in a row make it lost. The
//         mask is the target's shape at its start (the start mask, or the filled box when
//         started from a box) scaled to the tracker's box, clipped to the frame: the trackers
//         give only a box, and the start shape keeps the background inside the box out of the
//         inhibition for compact objects while costing one resize.
#pragma once

#include <memory>
#include <opencv2/core.hpp>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "tracker/correlation_options.h"
#include "tracker/tracker.h"

namespace attend {

// The tracker kinds. Adding one (CONTRIBUTING.md, "A tracker kind"): a value here, its class
// and its row (TrackerKindInfo) in a file of its own (as opencv_target_tracker.cc), the row's
// function declared in tracker_kinds.h and listed in TrackerKinds() (target_tracker.cc).
enum class TrackerKind { kBip, kKcf, kCsrt };
// "bip", "kcf", "csrt" (the tracker.kind key and the records).
const char* TrackerKindName(TrackerKind kind);
// Every kind's name, in the order of TrackerKinds().
const std::vector<std::string>& TrackerKindNames();
// The kind called `name`; false when there is none.
bool TrackerKindFromName(std::string_view name, TrackerKind* kind);

// Options of the OpenCV kinds (kcf, csrt).
struct OpenCvTrackerOptions {
  // A target whose tracker reports failure this many frames in a row is lost (it is occluded
  // before that).
  int lost_frames = 10;
  // kcf only: cv::TrackerKCF::Params::detect_thresh, the peak response below which KCF reports
  // failure (and does not update its model). OpenCV's default; 0 never reports a weak response.
  float kcf_detect_thresh = 0.5f;
  // "" when valid; otherwise names the field and the broken constraint.
  std::string Check() const;
  // The fields (util/option_fields.h), for Check and the configuration.
  static const OptionFields<OpenCvTrackerOptions>& Fields();
};

struct TargetTrackerOptions {
  TrackerKind kind = TrackerKind::kBip;
  // Used by kind bip only. The configuration's default is the bounded mode, which measures
  // best on real footage (docs/TRACKING.md, "Modes"); TrackerOptions alone defaults to the
  // thesis's tracker.
  TrackerOptions bip = BoundedTrackerOptions();
  // Used by kind bip in mode correlation only (tracker/correlation_tracker.h).
  CorrelationOptions correlation;
  OpenCvTrackerOptions opencv;  // used by kinds kcf and csrt only
  // "" when valid; otherwise names the field ("mode", "t_colour", "lost_frames", ...) and the
  // broken constraint. Checks only the options of `kind`.
  std::string Check() const;
  // The field `kind` (the blocks have their own tables).
  static const OptionFields<TargetTrackerOptions>& Fields();
};

// Every option block of TargetTrackerOptions with its field table, in the tracker section's
// order: visit(member, fields) for each. The configuration binds the blocks from here
// (VisitTracker, pipeline/options_io.cc); a kind's row says which keys of them it reads.
template <typename Visit>
void ForEachTrackerOptionBlock(Visit&& visit) {
  visit(&TargetTrackerOptions::bip, TrackerOptions::Fields());
  visit(&TargetTrackerOptions::correlation, CorrelationOptions::Fields());
  visit(&TargetTrackerOptions::opencv, OpenCvTrackerOptions::Fields());
}

class TargetTracker;

// A setting of its kind's options that `attend track` reports in its summary (track.json).
struct TrackerSetting {
  std::string key;
  std::variant<std::string, bool> value;
};

// A tracker kind's row: everything that differs by kind outside its class. Each kind's file
// defines its row (tracker_kinds.h).
struct TrackerKindInfo {
  TrackerKind kind;
  const char* name;               // tracker.kind's value, the records' and attend track's
  const char* colour_similarity;  // the record's similarity of a colour target
  const char* skin_similarity;    // ... and of a skin target
  // Which keys of the configuration's tracker section it reads (of its option block:
  // TrackerOptions for bip, OpenCvTrackerOptions for the OpenCV kinds); the others are refused
  // unless at their defaults while it is chosen.
  bool (*uses_key)(std::string_view key);
  // Its options' check: "" when valid, otherwise the field and the broken constraint.
  std::string (*check)(const TargetTrackerOptions& options);
  // The file under configs/ that `attend track` and attend.Tracker start it from (TrackConfigPath,
  // app/home.h); nullptr: the options' defaults.
  const char* config_file;
  // Why a start on a box gave no target, for attend track's error; nullptr: "the <name> tracker
  // cannot start on it".
  const char* no_target;
  // The settings attend track's summary reports.
  std::vector<TrackerSetting> (*settings)(const TargetTrackerOptions& options);
  std::unique_ptr<TargetTracker> (*create)(const TargetTrackerOptions& options, BipPool* pool);
};
// Every kind, one row each.
const std::vector<TrackerKindInfo>& TrackerKinds();
const TrackerKindInfo& TrackerKindOf(TrackerKind kind);

class TargetTracker {
 public:
  // A tracker of `options.kind`. ConfigError (util/error.h) when the options are not valid.
  // `pool`: the pyramids' pool of the kinds that build any (MultiTracker's); nullptr: their own.
  static std::unique_ptr<TargetTracker> Create(const TargetTrackerOptions& options,
                                               BipPool* pool = nullptr);

  virtual ~TargetTracker() = default;
  TargetTracker(const TargetTracker&) = delete;
  TargetTracker& operator=(const TargetTracker&) = delete;

  // Start a target in `frame` (8-bit BGR). Returns its id, or -1 when there is no usable target
  // (an empty mask, a box without pixels in the frame, or one the kind cannot start on, such as
  // a BIP target too thin for a template). `similarity` and `skin` (the frame's binary skin map,
  // CV_8UC1, needed by bip for skin targets) are ignored by the kinds that do not use them.
  //   box:    pixels of the frame; the bip kind segments it (MultiTracker::StartFromBox).
  //   mask:   CV_8UC1 of the frame's size, non-zero on the target.
  //   region: region `region` of the label image `labels` (CV_32SC1, frame size) of a
  //           segmentation of the frame (Segmentation::labels): its mask.
  virtual int StartFromBox(const cv::Mat& frame, const cv::Rect& box,
                           TrackSimilarity similarity = TrackSimilarity::kColour,
                           const cv::Mat& skin = cv::Mat()) = 0;
  virtual int StartFromMask(const cv::Mat& frame, const cv::Mat& mask,
                            TrackSimilarity similarity = TrackSimilarity::kColour,
                            const cv::Mat& skin = cv::Mat()) = 0;
  virtual int StartFromRegion(const cv::Mat& frame, const cv::Mat& labels, int region,
                              TrackSimilarity similarity = TrackSimilarity::kColour,
                              const cv::Mat& skin = cv::Mat());

  // Searches every target in `frame` and appends one result per target, in id order; a target
  // reported lost is removed afterwards. `skin` as for the starts. The results' `level` and
  // `overlap` are the BIP's (-1 and 0 for the other kinds); `roi` is the region searched (the
  // box for the OpenCV kinds, which search around it by their own padding).
  // `cylinder`, when given, is the frame's HSV cylinder image (BgrToCylinder, CV_32FC3, the
  // frame's size), which the bip kind then takes instead of converting its regions of interest
  // again; the values are the same either way.
  virtual void Track(const cv::Mat& frame, std::vector<TrackResult>* results,
                     const cv::Mat& skin = cv::Mat(), const cv::Mat& cylinder = cv::Mat()) = 0;

  // The target's pixels in the last frame it was started or searched in (CV_8UC1, frame size);
  // empty when it was not found there or the id is unknown.
  virtual cv::Mat Mask(int id) const = 0;
  // Stops tracking a target (unknown ids are ignored).
  virtual void Remove(int id) = 0;
  // Ids of the targets being tracked, ascending.
  virtual std::vector<int> ids() const = 0;

  virtual TrackerKind kind() const = 0;
  const char* name() const { return TrackerKindName(kind()); }
  // Milliseconds of the last Track() call, and the part of it spent segmenting (bip: the
  // over-segmentation of the regions of interest, MultiTracker::segmentation_milliseconds; 0
  // for the kinds that do not segment).
  virtual double milliseconds() const = 0;
  virtual double segmentation_milliseconds() const { return 0.0; }

 protected:
  TargetTracker() = default;
};

}  // namespace attend
