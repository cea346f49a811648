// The controller of `attend track` (SPEC 3.2, docs/TRACKING.md): a tracker of the kind
// `options.kind` over a sequence's left view or a plain folder of images, at their native size,
// started from boxes on the first frame of the range. It writes OUT/tracks.csv and
// OUT/track.json and hands every frame with its targets to observers, which write the dumps
// (masks, overlays). The command only parses its arguments.
#pragma once

#include <memory>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "io/sequence.h"
#include "tracker/target_tracker.h"

namespace attend {

struct TrackRequest {
  std::string sequence;  // a sequence folder (its left view) ...
  std::string images;    // ... or a plain folder of images
  int first_frame = 0;
  int last_frame = -1;          // -1: to the end
  std::string range_text;       // the range as the user gave it, for messages ("0:" when none)
  std::vector<cv::Rect> boxes;  // one target each, ids 1, 2, ... in order
  std::vector<std::string> box_texts;  // how each box was given, for messages
  std::string out;
  bool overwrite = false;  // replace a previous track output in `out`
  TargetTrackerOptions options;
};

// One target in one frame, as written and drawn.
struct TargetView {
  int id = 0;
  TrackState state = TrackState::kFound;
  cv::Rect box;
  cv::Rect roi;  // empty on the first frame
  cv::Mat mask;  // empty when not found
};

// Hears every frame of a tracking run once its targets are known, the first frame's as
// started. May throw OutputError; the run then stops, keeping tracks.csv of the frames done.
class TrackObserver {
 public:
  virtual ~TrackObserver() = default;
  virtual void OnFrame(const StereoFrame& frame, const std::vector<TargetView>& views) = 0;
};

// OUT/masks/<id>/<frame>.png: each target's mask, black when it is not found.
std::unique_ptr<TrackObserver> MakeMaskDump(const std::string& out);
// OUT/overlay/<frame>.png: the frame with each target tinted, its box and its search area.
std::unique_ptr<TrackObserver> MakeOverlayDump(const std::string& out);

// The keys of the configuration's tracker section (pipeline/options_io.h binds them to
// TargetTrackerOptions), without the "tracker." prefix.
const std::vector<std::string>& TrackerKeys();

// The options `attend track` builds its tracker from, and `attend eval-tracking --otb` its
// tracker called attend: the tracker section of `config`, or when `config` is "" of the kind's
// own file (TrackConfigPath: configs/track.yaml for bip; none, the defaults, for kcf and csrt),
// with `sets` ("tracker.KEY=VALUE", the value parsed as YAML) applied over it, read by the
// configuration's one binding, so that keys, ranges and messages are those of `attend run`.
// Only the tracker section is used (a whole configuration's other sections are checked all the
// same). ConfigError, naming `command`, for a --set outside tracker; ConfigError for an unknown
// key, a bad value or an option of another kind.
TargetTrackerOptions ResolveTrackerOptions(const std::string& config,
                                           const std::vector<std::string>& sets,
                                           const std::string& command);

// Checks the boxes against the first frame and starts every target before the output folder
// is touched, then tracks until the range ends or every target is lost. Returns the summary
// it also writes as OUT/track.json. ConfigError for a box outside the frame; InputError for
// a source without frames in the range, a box the tracker cannot start on, or a bad frame
// (tracks.csv then holds the frames done, and the message says which).
nlohmann::json TrackSequence(const TrackRequest& request,
                             const std::vector<TrackObserver*>& observers);

}  // namespace attend
