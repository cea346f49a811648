// `attend run`: the frame loop over a sequence. It reads each frame, runs the stages,
// records the frame in the run folder and reports progress; Ctrl-C (the stop flag) finishes
// the current frame and closes the run with `interrupted: true`.
#pragma once

#include <atomic>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "io/live_options.h"
#include "pipeline/attend_options.h"
#include "pipeline/stereo_check.h"
#include "util/timer.h"

namespace attend {

struct RunProgress {
  int done = 0;      // frames finished
  int total = -1;    // frames in the range; -1 when the source cannot tell
  double fps = 0.0;  // frames finished per second of wall time so far
};

class FramePipeline;
struct FrameRecord;
struct StereoFrame;

// Hears every frame of a run once the pipeline has processed it, before its record is
// appended to frames.jsonl: the dumps that output.dump asks for (maps, overlays, the overlay
// video) are such observers, and a caller can add its own (RunRequest::observers). The
// record is at the working size. An exception stops the run as a bad frame does: the frames
// done are kept and summary.json says why.
class RunObserver {
 public:
  virtual ~RunObserver() = default;
  virtual void OnFrame(const StereoFrame& frame, const FramePipeline& pipeline,
                       const FrameRecord& record) = 0;
};

struct RunRequest {
  AttendOptions options;     // sequence source already resolved
  std::string out_dir;       // the run folder
  bool overwrite = false;    // replace a previous run in out_dir
  std::string config_path;   // recorded in the summary
  std::string command_line;  // recorded in the summary
  std::string home;          // the folder of bundled files, for plugins' relative data paths
  const std::atomic<bool>* stop = nullptr;              // finish the frame, then stop
  std::function<void(const RunProgress&)> on_progress;  // after every frame
  std::vector<RunObserver*> observers;  // after the dumps, every frame (not owned)
  // The configuration is the shipped one (app/run_attention.h, ShippedFeatures): on a
  // monocular source the features that need stereo are left out, each named to on_left_out,
  // instead of refused (SPEC 3.1). Otherwise such a feature is a configuration error.
  bool stereo_features_optional = false;
  std::function<void(const std::string& feature)> on_left_out;
};

struct RunSummary {
  std::string dir;
  int frames = 0;
  double wall_seconds = 0.0;
  double fps = 0.0;    // frames / wall_seconds
  StageTimes mean_ms;  // per-stage mean milliseconds a frame
  int targets_attended = 0;
  bool interrupted = false;  // stopped before the end of the range
  std::string error;         // why it stopped early, when it did on an error
  std::vector<std::string> left_out;  // features left out: they need stereo, the source is mono
  // A live source: its capture (frames captured, dropped, unprocessed, how it ended) and the
  // latency from capture to record, ms.
  std::optional<LiveStatus> live;
  double mean_latency_ms = 0.0;
  double max_latency_ms = 0.0;
  // The top-down channels' detectors (FeatureMap::searched_pixels): by feature name, the mean
  // pixels searched a frame, at the working size's scale of each search.
  std::vector<std::pair<std::string, double>> searched_pixels;
  // A stereo source: its calibration and the row check of its first frame.
  std::optional<StereoSummary> stereo;

  // Two lines for the terminal: frames, fps, the slowest stages, where the outputs are.
  std::string BriefReport() const;
};

// Runs the loop. Problems found before the first frame (options, sequence) throw without
// creating the run folder. A bad frame later writes summary.json with the error and
// `interrupted: true`, then throws the InputError (exit status 3). A live source that stops
// delivering (live.timeout_s) ends the run as the end of a file does; summary.json's `live`
// says how it ended.
RunSummary RunSequence(const RunRequest& request);

// RUN/summary.json (SPEC 3.3) of a run of `request` over the sequence `info` that started at
// `started` (RunStartTime): frames, rates, mean stage times, the sequence, the pixels of the
// records and the maps, and where they apply the features left out, the detectors' searched
// pixels (`detectors`: each one's mean ms, its `feature.<name>` stage, and pixels a frame) and
// the live capture. `attend track-detections` writes its run's summary with it too.
nlohmann::ordered_json RunSummaryJson(const RunSummary& summary, const SequenceInfo& info,
                                      const RunRequest& request, const std::string& started);

// The local time now, as summary.json's `started` ("2026-12-04T14:34:57+0100").
std::string RunStartTime();

// runs/<YYYYmmdd-HHMMSS>-<config stem>-<sequence name> below `parent`, made unique.
std::string DefaultRunFolder(const std::string& parent, const std::string& config_path,
                             const std::string& sequence_name);

}  // namespace attend
