// attend.Pipeline, attend.run and the reference loop (python/bindings.h).
#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <atomic>
#include <cmath>
#include <cstdint>
#include <limits>
#include <ctime>
#include <memory>
#include <string>
#include <vector>

#include "app/home.h"
#include "app/run_attention.h"
#include "io/frame_record.h"
#include "io/sequence.h"
#include "io/stereo_calibration.h"
#include "pipeline/frame_pipeline.h"
#include "python/arrays.h"
#include "python/bindings.h"
#include "python/in_use.h"
#include "util/error.h"
#include "util/execution_context.h"
#include "util/limits.h"
#include "util/timer.h"

namespace attend::python {

namespace {

// One stage's milliseconds of a frame, as a dict in the stages' order.
py::dict TimingsDict(const StageTimes& times) {
  py::dict timings;
  for (const auto& [stage, ms] : times.stages()) timings[py::str(stage)] = ms;
  return timings;
}

// A stereo camera given by its rectified focal length, baseline and principal point (the
// nominal form of io/stereo_calibration.h) for attend.Pipeline's keywords; focal_px 0: none.
struct NominalCamera {
  double focal_px = 0.0;  // pixels of the input frames
  double baseline_m = 0.0;
  // The principal point, input pixels; NaN: the image centre ((width - 1) / 2, (height - 1) / 2).
  double cx = std::numeric_limits<double>::quiet_NaN();
  double cy = std::numeric_limits<double>::quiet_NaN();

  // ConfigError naming the keyword that is wrong.
  void Check() const {
    if (focal_px == 0.0 && baseline_m == 0.0) return;
    if (!(focal_px > 0.0) || !std::isfinite(focal_px)) {
      throw ConfigError("focal_px: must be a positive number of pixels (with baseline_m)");
    }
    if (!(baseline_m > 0.0) || !std::isfinite(baseline_m)) {
      throw ConfigError("baseline_m: must be a positive number of metres (with focal_px)");
    }
  }

  // The calibration of frames of `size`: NominalCalibration's, its principal point moved to
  // (cx, cy) when given.
  std::shared_ptr<const StereoCalibration> Calibration(cv::Size size) const {
    auto calibration = std::make_shared<StereoCalibration>(
        NominalCalibration(focal_px, baseline_m, size, "attend.Pipeline(focal_px, baseline_m)"));
    for (cv::Mat* p : {&calibration->P1, &calibration->P2}) {
      if (!std::isnan(cx)) p->at<double>(0, 2) = cx;
      if (!std::isnan(cy)) p->at<double>(1, 2) = cy;
    }
    if (!std::isnan(cx)) calibration->Q.at<double>(0, 3) = -calibration->cx();
    if (!std::isnan(cy)) calibration->Q.at<double>(1, 3) = -calibration->cy();
    return calibration;
  }
};

// The pipeline over frames handed in one at a time (attend.Pipeline). It is made when the
// first frame shows whether the source is stereo, and again by Reset.
class Pipeline {
 public:
  Pipeline(const AttendOptions& options, const NominalCamera& camera)
      : options_(options), camera_(camera), execution_(options.threads) {
    camera_.Check();
    registry_ = std::make_unique<FeatureRegistry>(LoadFeatureRegistry(options_.plugins));
    Make(/*stereo=*/true);  // so that a bad feature or parameter is reported now
  }

  py::dict Process(const py::array& left, const py::object& right, int index) {
    const InUse::Scope scope(&in_use_, "process()");
    // Records of frame numbers past this cannot be scored (attend eval refuses them).
    if (index < -1 || index > kMaxFrameNumber) {
      throw InputError("index: " + std::to_string(index) + " is not a frame number (0.." +
                       std::to_string(kMaxFrameNumber) + ", docs/LIMITS.md)");
    }
    StereoFrame frame;
    const cv::Mat native_left = BgrImage(left, "left");
    cv::Mat native_right;
    if (!right.is_none()) native_right = BgrImage(right.cast<py::array>(), "right");
    FrameRecord record;
    std::string record_json;
    {
      const py::gil_scoped_release release;
      const ScopedOpenCvThreads threads(execution_);
      const Stopwatch read;
      Begin(native_left, native_right);
      frame.index = index >= 0 ? index : next_index_;
      frame.left = Working(native_left);
      if (!native_right.empty()) frame.right = Working(native_right);
      record.frame = frame.index;
      record.timings.Add("read", read.ElapsedMs());
      pipeline_->Process(frame, &record);
      record_json = FrameRecordToJson(
          InputFromWorking(record, info_.scale_x, info_.scale_y, info_.native_size));
    }
    next_index_ = frame.index + 1;
    return Result(frame, record, record_json);
  }

  void Reset() {
    const InUse::Scope scope(&in_use_, "reset()");
    if (pipeline_ != nullptr && started_) pipeline_->EndSequence();
    started_ = false;
    next_index_ = options_.sequence.first_frame;
    Make(stereo_);
  }

  // The addresses of the buffers of the last frame's maps, to check that the arrays handed out
  // are those buffers (docs/PYTHON.md, "Arrays").
  py::dict buffers() {
    const InUse::Scope scope(&in_use_, "buffers()");
    py::dict addresses;
    auto address = [](const cv::Mat& map) { return reinterpret_cast<std::uintptr_t>(map.data); };
    addresses["saliency"] = address(pipeline_->saliency());
    addresses["inhibition"] = address(pipeline_->inhibition());
    addresses["inhibited"] = address(pipeline_->inhibited());
    for (size_t i = 0; i < pipeline_->features().size(); ++i) {
      const FeatureResult& feature = pipeline_->features()[i];
      addresses[py::str("features/" + feature.name)] = address(feature.map);
      addresses[py::str("normalised/" + feature.name)] = address(pipeline_->normalised()[i]);
    }
    return addresses;
  }

  py::dict info() {
    const InUse::Scope scope(&in_use_, "info");
    py::dict info;
    info["started"] = started_;
    info["stereo"] = stereo_;
    info["input_size"] = py::make_tuple(info_.native_size.width, info_.native_size.height);
    info["working_size"] = py::make_tuple(info_.size.width, info_.size.height);
    if (info_.calibration != nullptr) {
      const StereoCalibration& c = *info_.calibration;
      info["calibration"] = py::dict(py::arg("focal_px") = c.focal_px(),
                                     py::arg("baseline_m") = c.baseline_m(),
                                     py::arg("principal_point") = py::make_tuple(c.cx(), c.cy()));
    } else {
      info["calibration"] = py::none();
    }
    return info;
  }

 private:
  void Make(bool stereo) {
    FeatureSetup setup;
    setup.stereo = stereo;
    setup.home = AttendHome();
    pipeline_.reset();
    pipeline_ = std::make_unique<FramePipeline>(options_, *registry_, setup, &execution_);
    stereo_ = stereo;
  }

  // The first frame of a sequence fixes its size and whether it is stereo; later frames must
  // agree with it.
  void Begin(const cv::Mat& left, const cv::Mat& right) {
    const bool stereo = !right.empty();
    if (stereo && right.size() != left.size()) {
      throw InputError("right: its size " + std::to_string(right.cols) + "x" +
                       std::to_string(right.rows) + " differs from the left image's " +
                       std::to_string(left.cols) + "x" + std::to_string(left.rows));
    }
    if (started_) {
      if (left.size() != info_.native_size || stereo != stereo_) {
        throw InputError("frame " + std::to_string(next_index_) + ": " +
                         (stereo != stereo_ ? std::string(stereo_ ? "monocular" : "stereo") +
                                                  " after " +
                                                  (stereo_ ? "stereo" : "monocular") + " frames"
                                            : "its size differs from the sequence's first frame") +
                         "; call reset() to start a new sequence");
      }
      return;
    }
    if (stereo != stereo_) Make(stereo);
    SizeSequence(options_.sequence, left.size(), &info_);
    info_.stereo = stereo;
    // The camera's calibration is for the input frames; the pipeline takes the targets'
    // centroids and disparities there from the working size.
    info_.calibration = stereo && camera_.focal_px > 0.0 ? camera_.Calibration(left.size()) : nullptr;
    pipeline_->SetCamera(info_);
    if (next_index_ < 0) next_index_ = options_.sequence.first_frame;
    pipeline_->BeginSequence({"python", info_.size, stereo, next_index_});
    started_ = true;
  }

  // The frame at the working size, in a buffer of its own: the trackers keep frames.
  cv::Mat Working(const cv::Mat& native) const { return ToWorkingSize(native, info_.size); }

  py::dict Result(const StereoFrame& frame, const FrameRecord& record,
                  const std::string& record_json) const {
    py::dict result;
    result["frame"] = frame.index;
    result["record_json"] = record_json;
    result["saliency"] = MatArray(pipeline_->saliency());
    result["inhibition"] = MatArray(pipeline_->inhibition());
    result["inhibited"] = MatArray(pipeline_->inhibited());
    py::dict features, normalised, feature_ms;
    for (size_t i = 0; i < pipeline_->features().size(); ++i) {
      const FeatureResult& feature = pipeline_->features()[i];
      features[py::str(feature.name)] = MatArray(feature.map);
      normalised[py::str(feature.name)] = MatArray(pipeline_->normalised()[i]);
      feature_ms[py::str(feature.name)] = feature.milliseconds;
    }
    result["features"] = features;
    result["normalised"] = normalised;
    result["feature_ms"] = feature_ms;
    result["timings"] = TimingsDict(record.timings);
    result["working_size"] = py::make_tuple(info_.size.width, info_.size.height);
    return result;
  }

  const AttendOptions options_;
  const NominalCamera camera_;
  ExecutionContext execution_;  // the pipeline's threads and pools; outlives pipeline_
  std::unique_ptr<FeatureRegistry> registry_;  // outlives pipeline_, whose features it made
  std::unique_ptr<FramePipeline> pipeline_;
  SequenceInfo info_;
  bool stereo_ = true;
  bool started_ = false;
  int next_index_ = -1;
  // process() and reset() release the GIL while they change the pipeline: one call at a time.
  InUse in_use_{"attend.Pipeline",
                "use one Pipeline a thread (pipelines of their own run in parallel)"};
};

// This thread's CPU time in milliseconds (what Python's time.thread_time() reads).
double ThreadCpuMs() {
  timespec now{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
  return now.tv_sec * 1000.0 + now.tv_nsec / 1e6;
}

// The yardstick of bench/python_bench.py: the loop of `attend run` (pipeline/run.cc, RunFrame)
// over frames already in memory, less the decoding and the run folder: a new pipeline, then each
// frame copied into a new buffer (where the decoder would write it), through the pipeline, its
// record in input pixels and its JSON line. The frames are converted
// before the clock starts. Returns the milliseconds a frame, of the thread's CPU time and of
// the wall clock.
py::tuple ReferenceLoop(const AttendOptions& options, const py::list& frames) {
  std::vector<StereoFrame> inputs;
  cv::Size native;
  for (const py::handle pair : frames) {
    const py::tuple views = pair.cast<py::tuple>();
    StereoFrame frame;
    frame.index = static_cast<int>(inputs.size());
    frame.left = BgrImage(views[0].cast<py::array>(), "left");
    if (!views[1].is_none()) frame.right = BgrImage(views[1].cast<py::array>(), "right");
    native = frame.left.size();
    inputs.push_back(frame);
  }
  if (inputs.empty()) throw InputError("no frames");
  SequenceInfo info;
  SizeSequence(options.sequence, native, &info);
  info.stereo = !inputs[0].right.empty();
  for (StereoFrame& frame : inputs) {
    frame.left = ToWorkingSize(frame.left, info.size);
    if (info.stereo) frame.right = ToWorkingSize(frame.right, info.size);
  }
  double cpu_ms = 0.0, wall_ms = 0.0;
  size_t bytes = 0;
  {
    const py::gil_scoped_release release;
    ExecutionContext execution(options.threads);
    const ScopedOpenCvThreads threads(execution);
    const FeatureRegistry registry = LoadFeatureRegistry(options.plugins);
    FeatureSetup setup;
    setup.stereo = info.stereo;
    setup.home = AttendHome();
    FramePipeline pipeline(options, registry, setup, &execution);
    const double cpu_start = ThreadCpuMs();
    const Stopwatch wall;
    pipeline.BeginSequence({"reference", info.size, info.stereo, 0});
    for (const StereoFrame& held : inputs) {
      // attend run hands the pipeline each frame in a new buffer, the decoder's, as
      // Pipeline.process does (its copy of the caller's array): without this copy the loop
      // would read frames that left the caches long ago, and be the slower one.
      StereoFrame frame = held;
      frame.left = held.left.clone();
      if (info.stereo) frame.right = held.right.clone();
      FrameRecord record;
      record.frame = frame.index;
      pipeline.Process(frame, &record);
      bytes += FrameRecordToJson(
                   InputFromWorking(record, info.scale_x, info.scale_y, info.native_size))
                   .size();
    }
    pipeline.EndSequence();
    cpu_ms = (ThreadCpuMs() - cpu_start) / inputs.size();
    wall_ms = wall.ElapsedMs() / inputs.size();
  }
  return py::make_tuple(cpu_ms, wall_ms, bytes);
}

// attend.run: the configuration's run with its source replaced as asked; Ctrl-C in Python
// stops it after the current frame, as in the command line.
py::dict Run(const py::dict& source, const std::string& config,
             const std::vector<std::string>& overrides, const std::string& frames,
             const std::string& out, bool overwrite, double duration) {
  AttentionRunRequest request;
  request.config = config;
  request.sets = overrides;
  auto text = [&](const char* key) {
    return source.contains(key) && !source[key].is_none() ? py::str(source[key]).cast<std::string>()
                                                          : std::string();
  };
  auto number = [&](const char* key) {
    return source.contains(key) && !source[key].is_none() ? source[key].cast<int>() : -1;
  };
  SourceSpec& spec = request.source;
  spec.folder = text("sequence");
  spec.left_video = text("left_video");
  spec.right_video = text("right_video");
  spec.side_by_side_video = text("side_by_side_video");
  spec.video = text("video");
  spec.images = text("images");
  spec.camera = number("camera");
  spec.camera_right = number("camera_right");
  spec.gst = text("gst");
  spec.gst_right = text("gst_right");
  spec.calib = text("calib");
  spec.live.side_by_side =
      source.contains("side_by_side_live") && source["side_by_side_live"].cast<bool>();
  request.frames = frames;
  request.duration_s = duration;
  request.out = out;
  request.overwrite = overwrite;
  request.quiet = true;
  request.command_line = "python: attend.run";
  std::atomic<bool> stop = false;
  request.stop = &stop;
  // Between frames: a pending KeyboardInterrupt stops the run cleanly (interrupted: true).
  request.on_progress = [&stop](const RunProgress&) {
    const py::gil_scoped_acquire gil;
    if (PyErr_CheckSignals() != 0) stop = true;
  };
  RunSummary summary;
  {
    const AttendOptions options = ResolveRunOptions(request);
    const py::gil_scoped_release release;
    summary = RunAttention(request, options);
  }
  if (PyErr_Occurred() != nullptr) throw py::error_already_set();
  py::dict result;
  result["dir"] = summary.dir;
  result["frames"] = summary.frames;
  result["fps"] = summary.fps;
  result["interrupted"] = summary.interrupted;
  result["targets_attended"] = summary.targets_attended;
  return result;
}

}  // namespace

void RegisterPipeline(py::module_& m) {
  m.attr("max_frame_number") = kMaxFrameNumber;
  py::class_<Pipeline>(m, "Pipeline")
      .def(py::init([](const Configuration& c, double focal_px, double baseline_m, double cx,
                       double cy) {
             return std::make_unique<Pipeline>(c.options,
                                               NominalCamera{focal_px, baseline_m, cx, cy});
           }),
           py::arg("configuration"), py::arg("focal_px") = 0.0, py::arg("baseline_m") = 0.0,
           py::arg("cx") = std::numeric_limits<double>::quiet_NaN(),
           py::arg("cy") = std::numeric_limits<double>::quiet_NaN())
      .def("process", &Pipeline::Process, py::arg("left"), py::arg("right"), py::arg("index"))
      .def("reset", &Pipeline::Reset)
      .def("info", &Pipeline::info)
      .def("buffers", &Pipeline::buffers);

  m.def("run", [](const std::string& config, const std::vector<std::string>& overrides,
                  const py::dict& source, const std::string& frames, const std::string& out,
                  bool overwrite, double duration) {
    return Run(source, config, overrides, frames, out, overwrite, duration);
  });
  m.def("_reference_loop", [](const Configuration& c, const py::list& frames) {
    return ReferenceLoop(c.options, frames);
  });
}

}  // namespace attend::python
