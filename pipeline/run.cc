#include "pipeline/run.h"

#include <algorithm>
#include <chrono>
#include <ctime>
#include <filesystem>
#include <future>
#include <iomanip>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include "io/sequence.h"
#include "pipeline/frame_pipeline.h"
#include "pipeline/options_io.h"
#include "pipeline/overlay.h"
#include "pipeline/run_folder.h"
#include "pipeline/stereo_check.h"
#include "util/error.h"
#include "util/folder_lock.h"

namespace fs = std::filesystem;

namespace attend {

namespace {

std::string LocalTime(const char* format) {
  const std::time_t now = std::time(nullptr);
  std::tm local{};
  localtime_r(&now, &local);
  std::ostringstream out;
  out << std::put_time(&local, format);
  return out.str();
}

// The map dumps of SPEC 3.3 that output.dump asks for.
class MapDumps final : public RunObserver {
 public:
  MapDumps(const OutputOptions& output, RunFolder* folder) : output_(output), folder_(folder) {}

  void OnFrame(const StereoFrame& frame, const FramePipeline& pipeline,
               const FrameRecord&) override {
    const bool pfm = output_.WritesMapFormat("pfm");
    const bool png = output_.WritesMapFormat("png");
    if (output_.Dumps("regions")) {
      folder_->WriteImage("regions", frame.index, FalseColour(pipeline.context().Regions().labels));
    }
    if (output_.Dumps("features")) {
      for (size_t i = 0; i < pipeline.features().size(); ++i) {
        const FeatureResult& feature = pipeline.features()[i];
        folder_->WriteMap("features/" + feature.name, frame.index, feature.map,
                          pipeline.normalised()[i], pfm, png);
      }
    }
    if (output_.Dumps("saliency")) {
      folder_->WriteMap("saliency", frame.index, pipeline.saliency(), pipeline.saliency(), pfm,
                        png);
    }
    if (output_.Dumps("inhibition")) {
      folder_->WriteMap("inhibition", frame.index, pipeline.inhibition(), pipeline.inhibition(),
                        pfm, png);
    }
    if (output_.Dumps("background") && !pipeline.background().empty()) {
      folder_->WriteImage("background", frame.index,
                          DrawBackground(frame.left, pipeline.background()));
    }
    if (output_.Dumps("inhibited")) {
      folder_->WriteMap("inhibited", frame.index, pipeline.inhibited(), pipeline.inhibited(), pfm,
                        png);
    }
  }

 private:
  OutputOptions output_;
  RunFolder* folder_;
};

// The overlay of each frame (SPEC 3.3), and with output.video the overlay video.
class OverlayDump final : public RunObserver {
 public:
  OverlayDump(bool video, double fps, RunFolder* folder)
      : video_(video), fps_(fps), folder_(folder) {}

  void OnFrame(const StereoFrame& frame, const FramePipeline&, const FrameRecord& record) override {
    const cv::Mat overlay = DrawOverlay(frame.left, record);
    folder_->WriteImage("overlay", frame.index, overlay);
    if (video_) folder_->AppendVideoFrame("overlay", overlay, fps_);
  }

 private:
  bool video_;
  double fps_;
  RunFolder* folder_;
};

// The scanpath: each target's centre where it was first attended, in selection order.
void AppendScanpath(const FrameRecord& input, nlohmann::ordered_json* scanpath) {
  for (const int id : input.new_ids) {
    for (const TargetRecord& target : input.targets) {
      if (target.id != id) continue;
      const cv::Rect& b = target.bbox;
      scanpath->push_back({{"frame", input.frame},
                           {"id", id},
                           {"x", b.x + b.width / 2.0},
                           {"y", b.y + b.height / 2.0},
                           {"bbox", {b.x, b.y, b.width, b.height}}});
    }
  }
}

}  // namespace

std::string RunSummary::BriefReport() const {
  std::ostringstream out;
  out << std::fixed << std::setprecision(1);
  out << frames << " frames in " << wall_seconds << " s (" << fps << " frames/s)";
  if (interrupted) out << ", interrupted";
  out << "\nper frame:";
  for (const auto& [stage, ms] : mean_ms.stages()) {
    out << " " << stage << " " << std::setprecision(2) << ms << " ms";
  }
  if (live.has_value()) {
    out << "\nlive: " << live->captured << " frames captured, " << live->dropped
        << " dropped (queue " << live->queue << "), latency " << std::setprecision(1)
        << mean_latency_ms << " ms mean, " << max_latency_ms << " ms max; " << live->why;
  }
  out << "\noutputs: " << dir;
  return out.str();
}

std::string DefaultRunFolder(const std::string& parent, const std::string& config_path,
                             const std::string& sequence_name) {
  const std::string stem = config_path.empty() ? "config" : fs::path(config_path).stem().string();
  const std::string base =
      (fs::path(parent) / (LocalTime("%Y%m%d-%H%M%S") + "-" + stem + "-" + sequence_name)).string();
  std::string candidate = base;
  for (int suffix = 2; fs::exists(candidate); ++suffix) {
    candidate = base + "-" + std::to_string(suffix);
  }
  return candidate;
}

std::string RunStartTime() { return LocalTime("%Y-%m-%dT%H:%M:%S%z"); }

nlohmann::ordered_json RunSummaryJson(const RunSummary& summary, const SequenceInfo& info,
                                      const RunRequest& request, const std::string& started) {
  nlohmann::ordered_json timings = nlohmann::ordered_json::object();
  for (const auto& [stage, ms] : summary.mean_ms.stages()) timings[stage] = ms;
  nlohmann::ordered_json json = {{"frames", summary.frames},
          {"fps", summary.fps},
          {"wall_seconds", summary.wall_seconds},
          {"timings_ms", timings},
          {"targets_attended", summary.targets_attended},
          {"tracker", TrackerKindName(request.options.attention.tracker.kind)},
          {"interrupted", summary.interrupted},
          {"error", summary.error.empty() ? nlohmann::ordered_json()
                                          : nlohmann::ordered_json(summary.error)},
          {"sequence",
           {{"name", info.name},
            {"source", request.options.sequence.source.Describe()},
            {"stereo", info.stereo},
            {"frames_in_range", info.frame_count},
            {"native_size", {info.native_size.width, info.native_size.height}},
            {"size", {info.size.width, info.size.height}}}},
          // SPEC 3.3: boxes and areas of frames.jsonl are in input pixels; the dumped maps and
          // the overlays are at the working size. input = working * input_from_working.
          {"pixels",
           {{"records", "input"},
            {"maps", "working"},
            {"input_size", {info.native_size.width, info.native_size.height}},
            {"working_size", {info.size.width, info.size.height}},
            {"input_from_working", {1.0 / info.scale_x, 1.0 / info.scale_y}}}},
          {"config", request.config_path},
          {"command", request.command_line},
          {"started", started},
          {"attend_version", ATTEND_VERSION}};
  // Added only where they apply, so that a file run's summary keeps its fields.
  if (!summary.left_out.empty()) json["features_left_out"] = summary.left_out;
  if (!summary.searched_pixels.empty()) {
    // What each top-down channel's detector cost: its time and the pixels it searched a
    // frame, against the working frame's pixels (a network's pixels are at its own scale).
    nlohmann::ordered_json detectors = nlohmann::ordered_json::object();
    const double frame_pixels = static_cast<double>(info.size.area());
    for (const auto& [name, pixels] : summary.searched_pixels) {
      detectors[name] = {{"ms", summary.mean_ms.Get("feature." + name)},
                         {"searched_pixels", pixels},
                         {"frame_pixels", frame_pixels},
                         {"searched_fraction", frame_pixels > 0 ? pixels / frame_pixels : 0.0}};
    }
    json["detectors"] = detectors;
  }
  if (summary.stereo.has_value()) json["stereo"] = StereoSummaryJson(*summary.stereo);
  if (summary.live.has_value()) {
    const LiveStatus& live = *summary.live;
    json["live"] = {{"source", live.source},
                    {"queue", live.queue},
                    {"frames_captured", live.captured},
                    {"frames_dropped", live.dropped},
                    {"frames_unprocessed", live.unprocessed},
                    {"end", LiveEndName(live.end)},
                    {"why", live.why},
                    {"latency_ms",
                     {{"mean", summary.mean_latency_ms}, {"max", summary.max_latency_ms}}}};
  }
  return json;
}

namespace {

// Latencies from capture to record of a live run's frames, ms.
struct Latencies {
  double sum = 0.0;
  double max = 0.0;
  int count = 0;
};

// What a run gathers over its frames for its summary and scanpath.json.
struct RunTotals {
  StageTimes stages;  // the frames' timings, summed
  // The detectors' searched pixels by feature, summed over the frames.
  StageTimes searched;
  Latencies latencies;
  nlohmann::ordered_json scanpath = nlohmann::ordered_json::array();
  Stopwatch wall;  // from the first frame's read on
};

// A frame read from the source, with the time its read took.
struct ReadFrame {
  StereoFrame frame;
  bool more = false;  // false: the source has ended
  double read_ms = 0.0;
};

bool Read(FrameSource* source, ReadFrame* read) {
  const Stopwatch stage;
  read->more = source->Next(&read->frame);
  read->read_ms = stage.ElapsedMs();
  return read->more;
}

// The rest of a frame the pipeline has worked on (its record holds its frame number and
// times): the observers, its record appended to the run folder and the scanpath, its timings
// and its latency (live sources) to `totals`.
void RecordFrame(const StereoFrame& frame, const FramePipeline& pipeline,
                 const std::vector<RunObserver*>& observers, const SequenceInfo& info,
                 RunFolder* folder, RunTotals* totals, FrameRecord* record) {
  for (const FeatureResult& result : pipeline.features()) {
    if (result.searched_pixels >= 0.0) totals->searched.Add(result.name, result.searched_pixels);
  }
  Stopwatch stage;
  for (RunObserver* observer : observers) observer->OnFrame(frame, pipeline, *record);
  record->timings.Add("write", stage.ElapsedMs());
  // The pipeline and the overlay work at the working size; the record is written in the
  // pixels of the input frames (SPEC 3.3).
  FrameRecord input = InputFromWorking(*record, info.scale_x, info.scale_y, info.native_size);
  if (frame.captured != std::chrono::steady_clock::time_point{}) {
    input.latency_ms = std::chrono::duration<double, std::milli>(
                           std::chrono::steady_clock::now() - frame.captured)
                           .count();
    Latencies& latencies = totals->latencies;
    latencies.sum += input.latency_ms;
    latencies.max = std::max(latencies.max, input.latency_ms);
    ++latencies.count;
  }
  folder->AppendFrame(input);
  AppendScanpath(input, &totals->scanpath);
  for (const auto& [name, ms] : record->timings.stages()) totals->stages.Add(name, ms);
}

// After each frame: the counts and the caller's progress.
void CountFrame(const RunRequest& request, const SequenceInfo& info,
                const FramePipeline& pipeline, const RunTotals& totals, RunSummary* summary) {
  ++summary->frames;
  summary->targets_attended = pipeline.targets_attended();
  if (request.on_progress) {
    const double seconds = totals.wall.ElapsedMs() / 1000.0;
    request.on_progress(
        {summary->frames, info.frame_count, seconds > 0 ? summary->frames / seconds : 0.0});
  }
}

bool StopAsked(const RunRequest& request) {
  return request.stop != nullptr && request.stop->load();
}

// Runs `finish` on this thread while `ahead` (none when empty) runs on a thread of `pool`, and
// returns once both have ended: `ahead` uses what `finish`'s caller holds, so it is waited for
// even when `finish` throws. `finish`'s exception wins; else `ahead`'s is thrown.
void BesideAhead(ThreadPool* pool, std::function<void()> ahead,
                 const std::function<void()>& finish) {
  std::future<void> job;
  if (ahead) job = pool->Submit(std::move(ahead));
  try {
    finish();
  } catch (...) {
    if (job.valid()) job.wait();
    throw;
  }
  if (job.valid()) job.get();
}

// The frames of `source`, one after the other, until its end or a stop request (then
// `summary` says it was interrupted); what stops it otherwise is thrown.
void RunFrames(const RunRequest& request, FrameSource* source, FramePipeline* pipeline,
               const std::vector<RunObserver*>& observers, RunFolder* folder, RunTotals* totals,
               RunSummary* summary) {
  const SequenceInfo& info = source->info();
  source->WatchStop(request.stop);
  while (true) {
    if (StopAsked(request)) {
      summary->interrupted = true;
      return;
    }
    ReadFrame read;
    if (!Read(source, &read)) {
      // A live source stops waiting for its next frame when the run is asked to stop.
      if (StopAsked(request)) summary->interrupted = true;
      return;
    }
    FrameRecord record;
    record.frame = read.frame.index;
    record.timings.Add("read", read.read_ms);
    pipeline->Process(read.frame, &record);
    RecordFrame(read.frame, *pipeline, observers, info, folder, totals, &record);
    CountFrame(request, info, *pipeline, *totals, summary);
  }
}

// RunFrames on two frames at once (two threads or more): while this thread finishes frame t
// (its tracking, selection and records), a thread of `pool` reads frame t + 1 and runs its
// segmentation and features (FramePipeline::Ahead). The records, and what is kept when a frame
// fails, are those of RunFrames: frame t + 1's error is thrown after frame t is recorded.
void RunFramesOverlapped(const RunRequest& request, FrameSource* source, ThreadPool* pool,
                         FramePipeline* pipeline, const std::vector<RunObserver*>& observers,
                         RunFolder* folder, RunTotals* totals, RunSummary* summary) {
  const SequenceInfo& info = source->info();
  source->WatchStop(request.stop);
  const auto read_ahead = [source, pipeline](ReadFrame* read) {
    if (Read(source, read)) pipeline->Ahead(read->frame);
  };
  // Every frame taken from the source is finished and recorded, so that a live source's
  // counts add up (docs/LIVE.md); after a stop request no further frame is taken.
  ReadFrame current;
  if (!StopAsked(request)) read_ahead(&current);
  while (current.more) {
    ReadFrame next;
    std::function<void()> ahead;
    if (!StopAsked(request)) ahead = [&] { read_ahead(&next); };
    BesideAhead(pool, std::move(ahead), [&] {
      FrameRecord record;
      record.frame = current.frame.index;
      record.timings.Add("read", current.read_ms);
      pipeline->Finish(&record);
      RecordFrame(current.frame, *pipeline, observers, info, folder, totals, &record);
      CountFrame(request, info, *pipeline, *totals, summary);
    });
    current = std::move(next);
  }
  // A live source stops waiting for its next frame when the run is asked to stop.
  if (StopAsked(request)) summary->interrupted = true;
}

// The features of the run: on a monocular source with the shipped configuration, those that
// need stereo are left out of `options` (disabled there, so that RUN/config.yaml repeats the
// run as it was made), named in `summary` and to the request's on_left_out.
FeatureSetup SetUpFeatures(const RunRequest& request, const SequenceInfo& info,
                           const FeatureRegistry& registry, AttendOptions* options,
                           RunSummary* summary) {
  FeatureSetup setup;
  setup.home = request.home;
  if (!info.stereo && request.stereo_features_optional) {
    summary->left_out = LeaveOutStereoFeatures(registry, setup, &options->features);
    if (request.on_left_out) {
      for (const std::string& name : summary->left_out) request.on_left_out(name);
    }
  }
  setup.stereo = info.stereo;
  return setup;
}

// A live source captures from the moment it opens, and the first frames through a new pipeline
// cost several times a frame (their buffers' first pages, OpenCV's first calls: 161 ms for
// the first 320x240 frame of a live run against 18 ms later), while the capture queue fills
// and drops (docs/LIVE.md). So before the source opens, a pipeline of the run's configuration
// works on three frames of noise at the largest working size the options allow, as the run
// will (two at once with two threads), and is dropped: its buffers go back to the run's pools
// and the allocator, where the run's pipeline finds them. Nothing of it reaches the run; a
// failure here is left for the run to meet and report.
void WarmUpBeforeCapture(const RunRequest& request, const AttendOptions& options,
                         const FeatureRegistry& registry, ExecutionContext* execution) {
  const bool stereo = LiveIsStereo(options.sequence.source);
  const cv::Size size = options.sequence.resize == "native"
                            ? cv::Size(640, 480)
                            : cv::Size(options.sequence.width, options.sequence.height);
  try {
    AttendOptions warm_options = options;
    FeatureSetup setup;
    setup.home = request.home;
    if (!stereo && request.stereo_features_optional) {
      LeaveOutStereoFeatures(registry, setup, &warm_options.features);
    }
    setup.stereo = stereo;
    FramePipeline pipeline(warm_options, registry, setup, execution);
    cv::Mat left(size, CV_8UC3), right;
    cv::randu(left, cv::Scalar::all(0), cv::Scalar::all(256));
    if (stereo) {
      right = cv::Mat(size, CV_8UC3, cv::Scalar::all(0));
      left.colRange(4, size.width).copyTo(right.colRange(0, size.width - 4));
    }
    pipeline.BeginSequence({"warm-up", size, stereo, 0});
    std::vector<StereoFrame> frames(3);
    for (int i = 0; i < 3; ++i) {
      frames[i].index = i;
      frames[i].left = left;
      frames[i].right = right;
    }
    FrameRecord record;
    if (execution->threads() >= 2) {
      pipeline.Ahead(frames[0]);
      for (int i = 0; i < 3; ++i) {
        std::function<void()> ahead;
        if (i + 1 < 3) ahead = [&, i] { pipeline.Ahead(frames[i + 1]); };
        BesideAhead(execution->pool(), std::move(ahead), [&] { pipeline.Finish(&record); });
      }
    } else {
      for (const StereoFrame& frame : frames) pipeline.Process(frame, &record);
    }
    pipeline.EndSequence();
  } catch (const std::exception&) {
    // The run's own pipeline meets the same failure, and reports it with the run's context.
  }
}

// Fills the summary's timings, rates and live status from `totals`, and writes scanpath.json
// and summary.json.
void FinishRun(const RunRequest& request, const FrameSource& source, const RunTotals& totals,
               const std::string& started, RunFolder* folder, RunSummary* summary) {
  summary->wall_seconds = totals.wall.ElapsedMs() / 1000.0;
  summary->fps = summary->wall_seconds > 0 ? summary->frames / summary->wall_seconds : 0.0;
  for (const auto& [stage, ms] : totals.stages.stages()) {
    summary->mean_ms.Add(stage, summary->frames > 0 ? ms / summary->frames : 0.0);
  }
  for (const auto& [name, pixels] : totals.searched.stages()) {
    summary->searched_pixels.emplace_back(name, summary->frames > 0 ? pixels / summary->frames
                                                                    : 0.0);
  }
  summary->live = source.live_status();
  if (totals.latencies.count > 0) {
    summary->mean_latency_ms = totals.latencies.sum / totals.latencies.count;
    summary->max_latency_ms = totals.latencies.max;
  }
  folder->WriteJson("scanpath.json", totals.scanpath);
  folder->WriteSummary(RunSummaryJson(*summary, source.info(), request, started));
}

}  // namespace

RunSummary RunSequence(const RunRequest& request) {
  AttendOptions options = request.options;
  ExecutionContext execution(options.threads);
  const ScopedOpenCvThreads opencv_threads(execution);
  // A folder in use by another run is refused before the source opens and the warm-up works.
  if (!request.out_dir.empty()) RefuseFolderInUse(request.out_dir, "run");
  // A live source captures from the moment it opens, so its pipeline is warmed up before.
  // (Opened first and left unread while the warm-up works, a pipeline queues what it captures
  // meanwhile and hands it over in a burst: the run then starts behind, and drops.)
  std::optional<FeatureRegistry> loaded;
  if (options.sequence.source.IsLive()) {
    loaded.emplace(LoadFeatureRegistry(options.plugins));
    WarmUpBeforeCapture(request, options, *loaded, &execution);
  }
  std::unique_ptr<FrameSource> source = OpenFrameSource(options.sequence);
  // A stereo pair whose rows do not match is refused before anything is written.
  std::optional<StereoSummary> stereo = CheckStereoSource(options.sequence.check_rows, &source);
  const SequenceInfo& info = source->info();
  // Everything that can reject the configuration runs before the run folder exists.
  // With a second core the next frame is read and decoded, and its first stages run, while
  // this one is finished (RunFramesOverlapped), so no reader thread of its own (ReadAhead) is
  // needed: one more frame in memory, and a third thread on two cores, for no gain.
  if (!loaded) loaded.emplace(LoadFeatureRegistry(options.plugins));
  const FeatureRegistry& registry = *loaded;
  RunSummary summary;
  summary.stereo = std::move(stereo);
  const FeatureSetup setup = SetUpFeatures(request, info, registry, &options, &summary);
  FramePipeline pipeline(options, registry, setup, &execution);
  pipeline.SetCamera(info);

  const std::string out_dir = request.out_dir.empty()
                                  ? DefaultRunFolder("runs", request.config_path, info.name)
                                  : request.out_dir;
  RunFolder folder(out_dir, request.overwrite);
  folder.WriteConfig(OptionsToYaml(options));
  const std::string started = RunStartTime();

  // The dumps output.dump asks for, then the caller's observers.
  MapDumps map_dumps(options.output, &folder);
  OverlayDump overlay_dump(options.output.video, info.fps, &folder);
  std::vector<RunObserver*> observers = {&map_dumps};
  if (options.output.Dumps("overlay")) observers.push_back(&overlay_dump);
  observers.insert(observers.end(), request.observers.begin(), request.observers.end());

  summary.dir = folder.dir();
  RunTotals totals;
  try {
    pipeline.BeginSequence({info.name, info.size, info.stereo, options.sequence.first_frame});
    if (execution.threads() >= 2) {
      RunFramesOverlapped(request, source.get(), execution.pool(), &pipeline, observers,
                          &folder, &totals, &summary);
    } else {
      RunFrames(request, source.get(), &pipeline, observers, &folder, &totals, &summary);
    }
  } catch (const std::exception& e) {
    // Whatever stopped the loop, the frames done so far are kept and the summary says why.
    summary.interrupted = true;
    summary.error = e.what();
    try {
      FinishRun(request, *source, totals, started, &folder, &summary);
    } catch (const std::exception& summary_error) {
      // The summary could not be written either (a full disk, most often): the message says
      // what stopped the run, what is kept and what is missing.
      throw OutputError(std::string(e.what()) + "; " + summary_error.what() +
                        "; the run stopped after " + std::to_string(summary.frames) +
                        " frames, all of them in " + summary.dir +
                        "/frames.jsonl, and has no summary.json");
    }
    throw;
  }
  pipeline.EndSequence();
  try {
    FinishRun(request, *source, totals, started, &folder, &summary);
  } catch (const std::exception& summary_error) {
    throw OutputError(std::string(summary_error.what()) + "; the run finished its " +
                      std::to_string(summary.frames) + " frames, all of them in " + summary.dir +
                      "/frames.jsonl, but has no summary.json");
  }
  return summary;
}

}  // namespace attend
