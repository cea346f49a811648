// attend._attend: the C++ part of the Python module `attend` (docs/PYTHON.md). The package's
// Python files (python/attend/) give it its public shape; here are the pipeline, the stages on
// numpy arrays, the controllers of the commands and the errors. Every call that runs C++ work
// releases the GIL.
#include <pybind11/functional.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <atomic>
#include <cstdint>
#include <ctime>
#include <memory>
#include <opencv2/core/utility.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

#include "app/evaluate_fixations.h"
#include "app/evaluate_run.h"
#include "app/home.h"
#include "app/run_attention.h"
#include "app/write_report.h"
#include "config/param_block.h"
#include "features/disparity_feature.h"
#include "io/frame_record.h"
#include "io/image_file.h"
#include "io/pfm.h"
#include "io/sequence.h"
#include "pipeline/frame_pipeline.h"
#include "pipeline/options_io.h"
#include "pipeline/still_saliency.h"
#include "pyramid/segmentation.h"
#include "python/arrays.h"
#include "python/python_features.h"
#include "stereo/disparity.h"
#include "tracker/target_tracker.h"
#include "util/opencv_extra.h"
#include "util/error.h"
#include "util/json_text.h"
#include "util/timer.h"

namespace attend::python {

namespace {

// The configuration of `config` (a file; "" for the built-in defaults) with `overrides`
// ("key.path=value", as --set) applied in order: the command line's errors, word for word.
AttendOptions LoadConfiguration(const std::string& config,
                                const std::vector<std::string>& overrides) {
  if (!config.empty()) return LoadOptions(config, overrides);
  ParamBlock root = ParamBlock::Parse("", "<defaults>");
  for (const std::string& assignment : overrides) root.Override(assignment);
  return ReadOptions(root);
}

// Options bound for Python: the loaded configuration (its effective YAML by OptionsToYaml).
struct Configuration {
  AttendOptions options;
};

// One stage's milliseconds of a frame, as a dict in the stages' order.
py::dict TimingsDict(const StageTimes& times) {
  py::dict timings;
  for (const auto& [stage, ms] : times.stages()) timings[py::str(stage)] = ms;
  return timings;
}

// The pipeline over frames handed in one at a time (attend.Pipeline). It is made when the
// first frame shows whether the source is stereo, and again by Reset.
class Pipeline {
 public:
  explicit Pipeline(const AttendOptions& options) : options_(options) {
    if (options_.threads > 0) cv::setNumThreads(options_.threads);
    registry_ = std::make_unique<FeatureRegistry>(LoadFeatureRegistry(options_.plugins));
    Make(/*stereo=*/true);  // so that a bad feature or parameter is reported now
  }

  py::dict Process(const py::array& left, const py::object& right, int index) {
    StereoFrame frame;
    const cv::Mat native_left = BgrImage(left, "left");
    cv::Mat native_right;
    if (!right.is_none()) native_right = BgrImage(right.cast<py::array>(), "right");
    FrameRecord record;
    std::string record_json;
    {
      const py::gil_scoped_release release;
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
    if (pipeline_ != nullptr && started_) pipeline_->EndSequence();
    started_ = false;
    next_index_ = options_.sequence.first_frame;
    Make(stereo_);
  }

  // The addresses of the buffers of the last frame's maps, to check that the arrays handed out
  // are those buffers (docs/PYTHON.md, "Arrays").
  py::dict buffers() const {
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

  py::dict info() const {
    py::dict info;
    info["started"] = started_;
    info["stereo"] = stereo_;
    info["input_size"] = py::make_tuple(info_.native_size.width, info_.native_size.height);
    info["working_size"] = py::make_tuple(info_.size.width, info_.size.height);
    return info;
  }

 private:
  void Make(bool stereo) {
    FeatureSetup setup;
    setup.stereo = stereo;
    setup.home = AttendHome();
    pipeline_.reset();
    pipeline_ = std::make_unique<FramePipeline>(options_, *registry_, setup);
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
  std::unique_ptr<FeatureRegistry> registry_;  // outlives pipeline_, whose features it made
  std::unique_ptr<FramePipeline> pipeline_;
  SequenceInfo info_;
  bool stereo_ = true;
  bool started_ = false;
  int next_index_ = -1;
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
    if (options.threads > 0) cv::setNumThreads(options.threads);
    const FeatureRegistry registry = LoadFeatureRegistry(options.plugins);
    FeatureSetup setup;
    setup.stereo = info.stereo;
    setup.home = AttendHome();
    FramePipeline pipeline(options, registry, setup);
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

py::dict Saliency(const py::array& image, const AttendOptions& options, bool features) {
  const cv::Mat bgr = BgrImage(image, "image");
  std::vector<std::string> dropped;
  StillMaps maps;
  {
    const py::gil_scoped_release release;
    const StillSaliency still(options, AttendHome(), &dropped);
    maps = still.Compute(bgr, features, 0);
  }
  py::dict result;
  result["saliency"] = MatArray(maps.saliency);
  py::dict named;
  for (size_t i = 0; i < maps.features.size(); ++i) {
    named[py::str(maps.feature_names[i])] = MatArray(maps.features[i]);
  }
  result["features"] = named;
  result["left_out"] = dropped;
  result["working_size"] = py::make_tuple(maps.working_size.width, maps.working_size.height);
  return result;
}

// attend.imread: an image file as OpenCV reads it (BGR, or grey with `grey`), refused when
// it is cut short (io/image_file.h).
py::object ReadImage(const std::string& path, bool grey) {
  cv::Mat image;
  {
    const py::gil_scoped_release release;
    image = ReadNamedImageFile(path, grey ? cv::IMREAD_GRAYSCALE : cv::IMREAD_COLOR);
  }
  return MatArray(image);
}

// attend.imwrite: an 8-bit image (BGR or grey) to a file whose extension says the format.
void WriteImage(const std::string& path, const py::array& image) {
  const cv::Mat view = ImageView(py::array::ensure(image, py::array::c_style), "image");
  const py::gil_scoped_release release;
  WriteImageFile(path, view);
}

// attend.read_pfm and write_pfm: the run's lossless maps (io/pfm.h).
py::object ReadPfmArray(const std::string& path) {
  cv::Mat map;
  {
    const py::gil_scoped_release release;
    map = ReadPfm(path);
  }
  return MatArray(map);
}

void WritePfmArray(const std::string& path, const py::array& map) {
  const auto floats = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(map);
  const bool one = floats && floats.ndim() == 2;
  const bool three = floats && floats.ndim() == 3 && floats.shape(2) == 3;
  if (!one && !three) {
    throw InputError(path + ": a PFM map is an array of numbers, H x W or H x W x 3");
  }
  const cv::Mat view(static_cast<int>(floats.shape(0)), static_cast<int>(floats.shape(1)),
                     one ? CV_32FC1 : CV_32FC3, const_cast<float*>(floats.data()));
  const py::gil_scoped_release release;
  WritePfm(path, view);
}

// attend.frames: a frame folder's files in frame order and one frame as `attend run` reads it.
std::vector<std::string> FrameFiles(const std::string& folder) {
  return ListFrameFiles(folder, folder);
}

py::object FrameFile(int index, const std::string& path) {
  cv::Mat frame;
  {
    const py::gil_scoped_release release;
    frame = ReadFrameFile(index, path);
  }
  return MatArray(frame);
}

py::dict Segment(const py::array& image, const AttendOptions& options) {
  const cv::Mat bgr = BgrImage(image, "image");
  Segmentation segmentation;
  {
    const py::gil_scoped_release release;
    Segmenter segmenter(options.segmentation);
    segmenter.Segment(bgr, &segmentation);
  }
  return SegmentationDict(segmentation);
}

// The disparity options of `overrides` ("disparity.KEY=VALUE"), read as `attend disparity`
// reads its --set.
DisparityOptions DisparityKeywords(const std::vector<std::string>& overrides) {
  ParamBlock root = ParamBlock::Parse("", "<keywords>");
  for (const std::string& assignment : overrides) root.Override(assignment);
  const ParamBlock block = root.Child("disparity");
  root.CheckNoUnknownKeys();
  const DisparityOptions options = ReadDisparityOptions(block);
  block.CheckNoUnknownKeys();
  return options;
}

py::object Disparity(const py::array& left, const py::array& right,
                     const std::vector<std::string>& overrides) {
  const DisparityOptions options = DisparityKeywords(overrides);
  const cv::Mat l = ImageView(py::array::ensure(left, py::array::c_style), "left");
  const cv::Mat r = ImageView(py::array::ensure(right, py::array::c_style), "right");
  cv::Mat disparity;
  {
    const py::gil_scoped_release release;
    DisparityEstimator estimator(options);
    estimator.Compute(l, r, &disparity);
  }
  return MatArray(disparity);
}

// attend.Tracker: a tracker of the configuration's kind on numpy frames.
class Tracker {
 public:
  explicit Tracker(const AttendOptions& options)
      : tracker_(TargetTracker::Create(options.attention.tracker)) {}

  int Start(const py::array& frame, const std::vector<int>& box) {
    if (box.size() != 4) throw ConfigError("box: must be [x, y, width, height]");
    const cv::Mat bgr = BgrImage(frame, "frame");
    const py::gil_scoped_release release;
    return tracker_->StartFromBox(bgr, cv::Rect(box[0], box[1], box[2], box[3]));
  }

  int StartMask(const py::array& frame, const py::array& mask) {
    const cv::Mat bgr = BgrImage(frame, "frame");
    const cv::Mat m = ImageView(py::array::ensure(mask, py::array::c_style), "mask").clone();
    if (m.channels() != 1 || m.size() != bgr.size()) {
      throw InputError("mask: must be uint8 H x W of the frame's size");
    }
    const py::gil_scoped_release release;
    return tracker_->StartFromMask(bgr, m);
  }

  py::list Track(const py::array& frame) {
    const cv::Mat bgr = BgrImage(frame, "frame");
    std::vector<TrackResult> results;
    {
      const py::gil_scoped_release release;
      tracker_->Track(bgr, &results);
    }
    py::list list;
    for (const TrackResult& r : results) {
      py::dict target;
      target["id"] = r.id;
      target["state"] = TrackStateName(r.state);
      target["box"] = py::make_tuple(r.box.x, r.box.y, r.box.width, r.box.height);
      target["area"] = r.area;
      target["roi"] = py::make_tuple(r.roi.x, r.roi.y, r.roi.width, r.roi.height);
      list.append(target);
    }
    return list;
  }

  py::object Mask(int id) const { return MatArray(tracker_->Mask(id)); }
  void Remove(int id) { tracker_->Remove(id); }
  std::vector<int> ids() const { return tracker_->ids(); }
  std::string kind() const { return TrackerKindName(tracker_->kind()); }

 private:
  std::unique_ptr<TargetTracker> tracker_;
};

std::string EvalRun(const std::string& run, const std::string& gt) {
  nlohmann::ordered_json report;
  {
    const py::gil_scoped_release release;
    report = EvaluateRunFolder(run, gt);
  }
  return JsonText(report, -1);
}

py::dict EvalFixations(const std::vector<std::string>& maps, const std::string& dataset,
                       const std::string& out, const std::vector<std::string>& baselines,
                       double sigma, int max_side, int skip, int first) {
  EvalFixationsRequest request;
  request.maps = maps;
  request.dataset = dataset;
  request.out = out;
  request.baselines = baselines;
  request.sigma = sigma;
  request.max_side = max_side;
  request.skip = skip;
  request.first = first;
  request.quiet = true;
  request.command_line = "python: attend.eval_fixations";
  FixationEvaluation evaluation;
  {
    const py::gil_scoped_release release;
    evaluation = EvaluateFixations(request, {});
  }
  py::dict result;
  result["table"] = evaluation.table;
  result["failed"] = evaluation.failed;
  return result;
}

std::string Compare(const std::vector<std::string>& runs, const std::string& out,
                    bool overwrite, const std::vector<std::string>& gt) {
  ReportRequest request;
  request.runs = runs;
  request.out = out;
  request.gt = gt;
  request.overwrite = overwrite;
  request.command_line = "python: attend.compare";
  const py::gil_scoped_release release;
  return WriteReport(request).html;
}

py::list DescribeKeys() {
  py::list keys;
  for (const FieldDescription& field : DescribeConfiguration()) {
    py::dict key;
    key["key"] = field.key;
    key["type"] = field.type;
    key["range"] = field.range;
    key["default"] = field.fallback;
    key["doc"] = field.doc;
    keys.append(key);
  }
  return keys;
}

// The C++ errors as the package's exception classes (attend.ConfigError and the rest), each
// carrying the exit status the command line would give.
void RegisterErrors(py::module_& m) {
  static py::exception<Error> error(m, "Error");
  static py::exception<ConfigError> config(m, "ConfigError", error.ptr());
  static py::exception<OutputError> output(m, "OutputError", error.ptr());
  static py::exception<InputError> input(m, "InputError", error.ptr());
  static py::exception<PluginError> plugin(m, "PluginError", error.ptr());
  static py::exception<InternalError> internal(m, "InternalError", error.ptr());
  py::register_exception_translator([](std::exception_ptr pointer) {
    try {
      if (pointer) std::rethrow_exception(pointer);
    } catch (const ConfigError& e) {
      config(e.what());
    } catch (const OutputError& e) {
      output(e.what());
    } catch (const InputError& e) {
      input(e.what());
    } catch (const PluginError& e) {
      plugin(e.what());
    } catch (const InternalError& e) {
      internal(e.what());
    } catch (const Error& e) {
      error(e.what());
    }
  });
}

}  // namespace

}  // namespace attend::python

// The optional OpenCV module's entry point, compiled into this module (python/CMakeLists.txt).
extern "C" attend::cvextra::Module* attend_opencv_extra(int abi_version);

PYBIND11_MODULE(_attend, m) {
  using namespace attend;
  using namespace attend::python;
  cvextra::SetOpenCvExtra(attend_opencv_extra(cvextra::kAbiVersion));
  m.doc() = "attend's C++ core (docs/PYTHON.md); use the package attend";
  m.attr("__version__") = ATTEND_VERSION;
  RegisterErrors(m);
  RegisterPythonFeatures(m);

  py::class_<Configuration>(m, "Configuration")
      .def(py::init([](const std::string& config, const std::vector<std::string>& overrides) {
             return Configuration{LoadConfiguration(config, overrides)};
           }),
           py::arg("config"), py::arg("overrides"))
      .def("yaml", [](const Configuration& c) { return OptionsToYaml(c.options); });
  m.def("default_config_path", &DefaultConfigPath);
  m.def("segment_config_path", &SegmentConfigPath);
  m.def("track_config_path", [](const std::string& kind_name) {
    TrackerKind kind = TrackerKind::kBip;
    // An unknown kind is named by the configuration reader, with the kinds there are.
    return TrackerKindFromName(kind_name, &kind) ? TrackConfigPath(kind) : std::string();
  });
  m.def("home", &AttendHome);
  m.def("bundled_sequence", [](bool quiet) {
    const py::gil_scoped_release release;
    return EnsureBundledSequence(quiet);
  });
  m.def("describe_keys", &DescribeKeys);

  py::class_<Pipeline>(m, "Pipeline")
      .def(py::init([](const Configuration& c) { return std::make_unique<Pipeline>(c.options); }))
      .def("process", &Pipeline::Process, py::arg("left"), py::arg("right"), py::arg("index"))
      .def("reset", &Pipeline::Reset)
      .def("info", &Pipeline::info)
      .def("buffers", &Pipeline::buffers);

  m.def("run", [](const std::string& config, const std::vector<std::string>& overrides,
                  const py::dict& source, const std::string& frames, const std::string& out,
                  bool overwrite, double duration) {
    return Run(source, config, overrides, frames, out, overwrite, duration);
  });
  m.def("saliency", [](const py::array& image, const Configuration& c, bool features) {
    return Saliency(image, c.options, features);
  });
  m.def("segment", [](const py::array& image, const Configuration& c) {
    return Segment(image, c.options);
  });
  m.def("disparity", &Disparity);
  m.def("imread", &ReadImage, py::arg("path"), py::arg("grey") = false);
  m.def("imwrite", &attend::python::WriteImage, py::arg("path"), py::arg("image"));
  m.def("read_pfm", &ReadPfmArray, py::arg("path"));
  m.def("write_pfm", &WritePfmArray, py::arg("path"), py::arg("map"));
  m.def("_frame_files", &FrameFiles);
  m.def("_frame_file", &FrameFile);

  py::class_<Tracker>(m, "Tracker")
      .def(py::init([](const Configuration& c) { return std::make_unique<Tracker>(c.options); }))
      .def("start", &Tracker::Start)
      .def("start_mask", &Tracker::StartMask)
      .def("track", &Tracker::Track)
      .def("mask", &Tracker::Mask)
      .def("remove", &Tracker::Remove)
      .def_property_readonly("ids", &Tracker::ids)
      .def_property_readonly("kind", &Tracker::kind);

  m.def("_reference_loop", [](const Configuration& c, const py::list& frames) {
    return ReferenceLoop(c.options, frames);
  });
  m.def("eval_run", &EvalRun);
  m.def("eval_fixations", &EvalFixations);
  m.def("compare", &Compare);
}
