#include "app/track_detections.h"

#include <algorithm>
#include <memory>
#include <utility>
#include <vector>

#include "app/home.h"
#include "features/lazy_frame_context.h"
#include "pipeline/frame_pipeline.h"
#include "pipeline/options_io.h"
#include "pipeline/overlay.h"
#include "pipeline/run_folder.h"
#include "util/error.h"
#include "util/strings.h"

namespace attend {

namespace {

// What the tracks are: the tracker and similarity fields of their records and summary.json.
constexpr const char* kTracker = "detections";
constexpr const char* kSimilarity = "iou";

// The index of the feature called `name` in `features`, -1 when there is none.
int FindFeature(const std::vector<FeatureSpec>& features, const std::string& name) {
  for (size_t i = 0; i < features.size(); ++i) {
    if (features[i].name == name) return static_cast<int>(i);
  }
  return -1;
}

// The channel's spec in `options` (resolved with `request`), refused with a ConfigError when
// it is missing, disabled or reports no detections (created once here to ask it, which also
// checks its keys and model files against the configuration as written).
void CheckChannel(const DetectionTracksRequest& request, const AttendOptions& options) {
  const std::string config = request.run.config.empty() ? DefaultConfigPath() : request.run.config;
  const std::string& name = request.feature;
  const int index = FindFeature(options.features, name);
  if (index < 0) {
    std::vector<std::string> names;
    for (const FeatureSpec& spec : options.features) names.push_back(spec.name);
    throw ConfigError(config + ": features: no feature named '" + name + "'" +
                      DidYouMean(name, names) + " (the list has " +
                      (names.empty() ? std::string("none") : Join(names, ", ")) +
                      "); attend track-detections runs the configuration's top-down channel "
                      "(people, faces, objects), named by --feature");
  }
  const FeatureSpec& spec = options.features[index];
  if (!spec.enabled) {
    spec.params.Fail("enabled", "the feature '" + name +
                                    "' is disabled; attend track-detections runs an enabled "
                                    "channel only (--set features." +
                                    name + ".enabled=true)");
  }
  FeatureSetup setup;
  setup.home = AttendHome();
  const FeatureRegistry registry = LoadFeatureRegistry(options.plugins);
  if (registry.Create(spec, setup)->searched_pixels() < 0.0) {
    throw ConfigError(spec.params.Where() + ": features." + name + ": the feature '" + name +
                      "' reports no detections (it is not a top-down channel such as people, "
                      "faces or objects); name one with --feature");
  }
}

// A track's record: the detection's box (working pixels), its box area, and the detector's
// confidence as its saliency (the channel's map is the box filled with its confidence).
TargetRecord TrackRecord(const LinkedBox& linked, const Detection& detection) {
  TargetRecord target;
  target.id = linked.id;
  target.bbox = linked.box;
  target.area = linked.box.area();
  target.saliency = detection.confidence;
  target.state = linked.started ? TargetState::kNew : TargetState::kTracked;
  target.similarity = kSimilarity;
  target.tracker = kTracker;
  target.label = detection.label;
  return target;
}

// What the frame loop keeps for the summary.
struct PeerTotals {
  StageTimes stages;           // the frames' timings, summed
  double searched_pixels = 0;  // the channel's, summed
  Stopwatch wall;
};

// The peer's frame loop and what it writes, around one channel and one linker.
class DetectionTracks {
 public:
  DetectionTracks(const DetectionTracksRequest& request, const AttendOptions& options,
                  const FeatureRegistry& registry, const FeatureSetup& setup)
      : request_(request),
        options_(options),
        channel_(options.features, registry, setup),
        linker_(request.link) {}

  // The frames of `source` into `folder` until its end or a stop request; `summary` gets the
  // frames done and whether it was interrupted.
  void Run(FrameSource* source, RunFolder* folder, RunSummary* summary) {
    const SequenceInfo& info = source->info();
    channel_.BeginSequence({info.name, info.size, info.stereo, options_.sequence.first_frame});
    source->WatchStop(request_.run.stop);
    while (!Stopped()) {
      if (!Frame(source, folder)) break;
      ++summary->frames;
      summary->targets_attended = linker_.tracks_started();
      if (request_.run.on_progress) {
        const double seconds = totals_.wall.ElapsedMs() / 1000.0;
        request_.run.on_progress(
            {summary->frames, info.frame_count, seconds > 0 ? summary->frames / seconds : 0.0});
      }
    }
    summary->interrupted = Stopped();
    channel_.EndSequence();
  }

  const PeerTotals& totals() const { return totals_; }

 private:
  bool Stopped() const { return request_.run.stop != nullptr && request_.run.stop->load(); }

  // The next frame: its detections, linked, recorded in input pixels; false at the end.
  bool Frame(FrameSource* source, RunFolder* folder) {
    FrameRecord record;
    Stopwatch stage;
    StereoFrame frame;
    if (!source->Next(&frame)) return false;
    record.frame = frame.index;
    record.timings.Add("read", stage.ElapsedMs());

    context_.Reset(frame.index, frame.left, frame.right);
    channel_.Compute(context_);
    const FeatureResult& result = channel_.results().front();
    record.timings.Add("feature." + result.name, result.milliseconds);
    totals_.searched_pixels += std::max(0.0, result.searched_pixels);

    stage.Restart();
    boxes_.clear();
    for (const Detection& detection : result.detections) boxes_.push_back(detection.box);
    for (const LinkedBox& linked : linker_.Link(boxes_)) {
      record.targets.push_back(TrackRecord(linked, result.detections[linked.detection]));
      if (linked.started) record.new_ids.push_back(linked.id);
    }
    record.timings.Add("link", stage.ElapsedMs());

    stage.Restart();
    if (options_.output.Dumps("overlay")) {
      folder->WriteImage("overlay", frame.index, DrawOverlay(frame.left, record));
    }
    const SequenceInfo& info = source->info();
    folder->AppendFrame(InputFromWorking(record, info.scale_x, info.scale_y, info.native_size));
    record.timings.Add("write", stage.ElapsedMs());
    for (const auto& [name, ms] : record.timings.stages()) totals_.stages.Add(name, ms);
    return true;
  }

  const DetectionTracksRequest& request_;
  const AttendOptions& options_;
  FeatureSet channel_;
  DetectionLinker linker_;
  LazyFrameContext context_;
  std::vector<cv::Rect> boxes_;
  PeerTotals totals_;
};

// summary.json: attend run's (RunSummaryJson), the tracker named as the peer's, and the
// linker's settings.
void FinishPeer(const RunRequest& run, const DetectionTracksRequest& request,
                const FrameSource& source, const PeerTotals& totals, const std::string& started,
                RunFolder* folder, RunSummary* summary) {
  summary->wall_seconds = totals.wall.ElapsedMs() / 1000.0;
  summary->fps = summary->wall_seconds > 0 ? summary->frames / summary->wall_seconds : 0.0;
  const double frames = std::max(1, summary->frames);
  for (const auto& [stage, ms] : totals.stages.stages()) summary->mean_ms.Add(stage, ms / frames);
  summary->searched_pixels = {{request.feature, totals.searched_pixels / frames}};
  nlohmann::ordered_json json = RunSummaryJson(*summary, source.info(), run, started);
  json["tracker"] = kTracker;
  json["linking"] = {{"feature", request.feature},
                     {"match_iou", request.link.match_iou},
                     {"max_missed", request.link.max_missed},
                     {"velocity_frames", request.link.velocity_frames}};
  folder->WriteSummary(json);
}

}  // namespace

AttendOptions ResolveDetectorOptions(const DetectionTracksRequest& request) {
  const std::string error = request.link.Check();
  if (!error.empty()) throw ConfigError("linking: " + error);
  const AttendOptions plain = ResolveRunOptions(request.run);
  CheckChannel(request, plain);
  // The same configuration with the channel on the whole frame every frame: set after the
  // overrides, so that they win over the file's and the command line's.
  AttentionRunRequest forced = request.run;
  const std::string key =
      "features." + std::to_string(FindFeature(plain.features, request.feature)) + ".";
  forced.sets.push_back(key + "gate=frame");
  forced.sets.push_back(key + "every=1");
  AttendOptions options = ResolveRunOptions(forced);
  const FeatureSpec channel = options.features[FindFeature(options.features, request.feature)];
  options.features = {channel};
  return options;
}

RunSummary TrackDetections(const DetectionTracksRequest& request, const AttendOptions& options) {
  std::unique_ptr<FrameSource> source = OpenFrameSource(options.sequence);
  ExecutionContext execution(options.threads);
  const ScopedOpenCvThreads opencv_threads(execution);
  if (execution.threads() >= 2 && !options.sequence.source.IsLive()) {
    source = ReadAhead(std::move(source));
  }
  const SequenceInfo& info = source->info();
  const FeatureRegistry registry = LoadFeatureRegistry(options.plugins);
  FeatureSetup setup;
  setup.home = AttendHome();
  setup.stereo = info.stereo;
  DetectionTracks peer(request, options, registry, setup);

  RunRequest run;
  run.options = options;
  run.config_path = request.run.config.empty() ? DefaultConfigPath() : request.run.config;
  run.command_line = request.run.command_line;
  const std::string out_dir = !request.run.out.empty()
                                  ? request.run.out
                                  : DefaultRunFolder("runs", run.config_path, info.name);
  RunFolder folder(out_dir, request.run.overwrite);
  folder.WriteConfig(OptionsToYaml(options));
  const std::string started = RunStartTime();
  RunSummary summary;
  summary.dir = folder.dir();
  try {
    peer.Run(source.get(), &folder, &summary);
  } catch (const std::exception& e) {
    // The frames done are kept and the summary says why the run stopped (as attend run's).
    summary.interrupted = true;
    summary.error = e.what();
    FinishPeer(run, request, *source, peer.totals(), started, &folder, &summary);
    throw;
  }
  FinishPeer(run, request, *source, peer.totals(), started, &folder, &summary);
  return summary;
}

}  // namespace attend
