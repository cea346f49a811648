#include "python/python_features.h"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cmath>
#include <filesystem>
#include <memory>
#include <string>
#include <variant>
#include <vector>

#include "config/declared_options.h"
#include "config/param_block.h"
#include "features/builtin.h"
#include "features/feature_map.h"
#include "features/python_plugins.h"
#include "python/arrays.h"
#include "python/in_use.h"
#include "util/error.h"

namespace attend::python {

namespace {

py::module_ Module() { return py::module_::import("attend._attend"); }

// The Python traceback of `error`, as Python prints it.
std::string Traceback(py::error_already_set& error) {
  try {
    const py::object lines = py::module_::import("traceback")
                                 .attr("format_exception")(error.type(), error.value(),
                                                           error.trace());
    return py::str("").attr("join")(lines).cast<std::string>();
  } catch (py::error_already_set&) {
    return error.what();
  }
}

// The built-in features, whose names Python features may not take and whose maps
// FeatureContext.builtin computes.
const FeatureRegistry& Builtins() {
  static const FeatureRegistry* const registry = new FeatureRegistry(BuiltinFeatures());
  return *registry;
}

// What a Python feature sees of a frame (FrameContext): views of the context's buffers,
// usable while its compute() runs.
class ContextView {
 public:
  explicit ContextView(const FrameContext* context) : context_(context) {}

  const FrameContext& context() const {
    if (context_ == nullptr) {
      throw PluginError("a feature context was used after its compute() returned; keep copies "
                        "(numpy.array(...)) of what a later frame needs");
    }
    return *context_;
  }
  void Close() { context_ = nullptr; }

  py::object Regions() {
    if (regions_.is_none()) {
      const Segmentation* segmentation = nullptr;
      {
        const InUse::Scope scope(&in_use_, "regions");
        const py::gil_scoped_release release;
        segmentation = &context().Regions();
      }
      regions_ = SegmentationDict(*segmentation);
    }
    return regions_;
  }

  py::object Cylinder() const {
    return Computed("cylinder",
                    [](const FrameContext& c) -> const cv::Mat& { return c.Cylinder(); });
  }
  py::object Tsl() const {
    return Computed("tsl", [](const FrameContext& c) -> const cv::Mat& { return c.Tsl(); });
  }
  py::object Disparity() const {
    if (!context().stereo()) return py::none();
    return Computed("disparity", [](const FrameContext& c) -> const cv::Mat& {
      return c.Disparity(c.disparity_options());
    });
  }

  // A built-in feature's map on this frame, computed by a feature of that name with its
  // default parameters (one made for this call: stateless features only).
  py::object Builtin(const std::string& name) const {
    FeatureSpec spec;
    spec.name = name;
    FeatureSetup setup;
    setup.stereo = context().stereo();
    cv::Mat map;
    {
      const InUse::Scope scope(&in_use_, "builtin()");
      const py::gil_scoped_release release;
      std::unique_ptr<FeatureMap> feature = Builtins().Create(spec, setup);
      feature->Compute(context(), &map);
    }
    return MatArray(map);
  }

 private:
  // A map the context computes on demand (`get`), computed without the GIL, as a read-only
  // array over the context's buffer.
  template <typename Get>
  py::object Computed(const char* name, const Get& get) const {
    const FrameContext& frame = context();
    const cv::Mat* map = nullptr;
    {
      const InUse::Scope scope(&in_use_, name);
      const py::gil_scoped_release release;
      map = &get(frame);
    }
    return MatArray(*map, false);
  }

  const FrameContext* context_;
  py::object regions_ = py::none();
  // The maps computed on demand are computed without the GIL, and the frame's context computes
  // each once: a thread that the feature started may not compute one beside its compute().
  mutable InUse in_use_{"feature context",
                        "compute the maps a feature needs on the thread of its compute()"};
};

// A registered Python class's instance as a feature plugin.
class PythonFeature final : public FeatureMap {
 public:
  PythonFeature(std::string name, py::object instance, bool needs_stereo, bool reads_regions)
      : name_(std::move(name)),
        instance_(std::move(instance)),
        needs_stereo_(needs_stereo),
        reads_regions_(reads_regions) {}

  ~PythonFeature() override {
    if (Py_IsInitialized() == 0 || _Py_IsFinalizing() != 0) {
      instance_.release();  // the interpreter is going away: nothing to give back
      return;
    }
    const py::gil_scoped_acquire gil;
    instance_ = py::object();
  }

  void BeginSequence(const SequenceStart& start) override {
    const py::gil_scoped_acquire gil;
    if (!py::hasattr(instance_, "begin_sequence")) return;
    py::dict info;
    info["name"] = start.name;
    info["size"] = py::make_tuple(start.size.width, start.size.height);
    info["stereo"] = start.stereo;
    info["first_frame"] = start.first_frame;
    Call("begin_sequence", [&] { instance_.attr("begin_sequence")(info); });
  }

  void EndSequence() override {
    const py::gil_scoped_acquire gil;
    if (!py::hasattr(instance_, "end_sequence")) return;
    Call("end_sequence", [&] { instance_.attr("end_sequence")(); });
  }

  void Compute(const FrameContext& context, cv::Mat* out) override {
    const py::gil_scoped_acquire gil;
    auto view = std::make_shared<ContextView>(&context);
    py::object result;
    Call("compute", [&] { result = instance_.attr("compute")(py::cast(view)); });
    view->Close();
    const std::string what = "feature '" + name_ + "' (Python): compute()";
    MapFromObject(result, context.size(), what, out);
    CheckFinite(*out, what, context.frame_index());
  }

  bool NeedsStereo() const override { return needs_stereo_; }
  bool ReadsAttentionRegions() const override { return reads_regions_; }

 private:
  // Runs `call`; a Python exception becomes a PluginError with the feature's name and the
  // traceback.
  template <typename Function>
  void Call(const char* method, const Function& call) {
    try {
      call();
    } catch (py::error_already_set& e) {
      throw PluginError("feature '" + name_ + "' (Python): " + method + "() raised:\n" +
                        Traceback(e));
    }
  }

  // PluginError naming the first pixel (row by row) of `map` that is NaN or infinite: the
  // feature's own fault, reported as such (exit 4), not as a configuration error.
  static void CheckFinite(const cv::Mat& map, const std::string& what, int frame) {
    int bad = 0, first_x = -1, first_y = -1;
    float first = 0.0f;
    for (int y = 0; y < map.rows; ++y) {
      const float* row = map.ptr<float>(y);
      for (int x = 0; x < map.cols; ++x) {
        if (std::isfinite(row[x])) continue;
        if (bad++ == 0) first_x = x, first_y = y, first = row[x];
      }
    }
    if (bad == 0) return;
    throw PluginError(what + ": returned a map with " +
                      (std::isnan(first) ? "NaN" : first > 0 ? "inf" : "-inf") +
                      " at pixel (x " + std::to_string(first_x) + ", y " +
                      std::to_string(first_y) + ") of frame " + std::to_string(frame) + " (" +
                      std::to_string(bad) + " of its " + std::to_string(map.total()) +
                      " values are not finite); a feature map must be finite everywhere");
  }

  std::string name_;
  py::object instance_;
  bool needs_stereo_;
  bool reads_regions_;
};

// Reads the options a class declares (its `options` dict of defaults) from the feature's
// entry, each with the type of its default; keys it does not declare are left for
// CheckNoUnknownKeys to report.
py::dict ReadDeclaredOptions(const std::string& name, const py::object& cls,
                             const ParamBlock& params) {
  py::dict values;
  if (!py::hasattr(cls, "options")) return values;
  const py::object declared = cls.attr("options");
  if (!py::isinstance<py::dict>(declared)) {
    throw PluginError("feature '" + name + "' (Python): its class's `options` must be a dict of "
                      "option names and defaults");
  }
  // The class's options as a table built at run time, read in config/ like every other.
  std::vector<DeclaredOption> table;
  for (const auto& [key_object, fallback] : declared.cast<py::dict>()) {
    const std::string key = py::str(key_object).cast<std::string>();
    if (py::isinstance<py::bool_>(fallback)) {
      table.push_back({key, fallback.cast<bool>()});
    } else if (py::isinstance<py::int_>(fallback)) {
      table.push_back({key, fallback.cast<int>()});
    } else if (py::isinstance<py::float_>(fallback)) {
      table.push_back({key, fallback.cast<double>()});
    } else if (py::isinstance<py::str>(fallback)) {
      table.push_back({key, fallback.cast<std::string>()});
    } else if (py::isinstance<py::list>(fallback) || py::isinstance<py::tuple>(fallback)) {
      const py::sequence list = fallback.cast<py::sequence>();
      bool strings = list.size() > 0;
      for (const py::handle element : list) strings = strings && py::isinstance<py::str>(element);
      if (strings) {
        table.push_back({key, list.cast<std::vector<std::string>>()});
      } else {
        table.push_back({key, list.cast<std::vector<double>>()});
      }
    } else {
      throw PluginError("feature '" + name + "' (Python): option '" + key +
                        "' has a default of type " +
                        py::str(py::type::of(fallback).attr("__name__")).cast<std::string>() +
                        "; options are bool, int, float, str or lists of numbers or strings");
    }
  }
  ReadDeclaredOptions(params, &table);
  for (const DeclaredOption& option : table) {
    std::visit([&](const auto& value) { values[py::str(option.key)] = py::cast(value); },
               option.value);
  }
  return values;
}

std::unique_ptr<FeatureMap> CreatePythonFeature(const std::string& name, const ParamBlock& params,
                                                const FeatureSetup&) {
  const py::gil_scoped_acquire gil;
  const py::dict features = Module().attr("_features");
  if (!features.contains(name)) {
    throw ConfigError(params.Where("name") + ": the Python feature '" + name +
                      "' is no longer registered");
  }
  const py::object cls = features[py::str(name)].cast<py::tuple>()[0];
  const py::dict options = ReadDeclaredOptions(name, cls, params);
  py::object instance;
  try {
    instance = cls(**options);
  } catch (py::error_already_set& e) {
    throw PluginError("feature '" + name + "' (Python): creating it raised:\n" + Traceback(e));
  }
  const bool needs_stereo =
      py::hasattr(instance, "needs_stereo") && py::bool_(instance.attr("needs_stereo"));
  // Unless it says otherwise, a feature may read context.attention_regions, so it waits for
  // the attention stage's last frame (FeatureMap::ReadsAttentionRegions).
  const bool reads_regions = !py::hasattr(instance, "reads_attention_regions") ||
                             py::bool_(instance.attr("reads_attention_regions"));
  return std::make_unique<PythonFeature>(name, std::move(instance), needs_stereo, reads_regions);
}

// Adds the registered Python feature `name` to `registry` unless it has one of that name.
void AddToRegistry(const std::string& name, const py::tuple& entry, FeatureRegistry* registry) {
  if (registry->Find(name) != nullptr) return;
  registry->SetOrigin(entry[2].cast<std::string>());
  try {
    registry->Add(name, entry[1].cast<std::string>(),
                  [name](const ParamBlock& params, const FeatureSetup& setup) {
                    return CreatePythonFeature(name, params, setup);
                  });
  } catch (...) {
    registry->SetOrigin("built-in");
    throw;
  }
  registry->SetOrigin("built-in");
}

void AddRegistered(FeatureRegistry* registry) {
  const py::gil_scoped_acquire gil;
  const py::dict features = Module().attr("_features");
  for (const auto& [name, entry] : features) {
    AddToRegistry(py::str(name).cast<std::string>(), entry.cast<py::tuple>(), registry);
  }
}

// Runs the plugin file; the features it registers get the file as their origin.
void LoadFile(const std::string& path, const std::string& where, FeatureRegistry* registry) {
  const py::gil_scoped_acquire gil;
  const std::string origin = std::filesystem::absolute(path).lexically_normal().string();
  py::module_ module = Module();
  const py::dict features = module.attr("_features");
  module.attr("_loading") = origin;
  try {
    py::module_::import("runpy").attr("run_path")(origin, py::arg("run_name") = "attend_plugin");
  } catch (py::error_already_set& e) {
    module.attr("_loading") = py::none();
    if (e.matches(module.attr("Error"))) {
      throw ConfigError(where + ": plugin " + path + ": " + py::str(e.value()).cast<std::string>());
    }
    throw PluginError(where + ": plugin " + path + ": running it raised:\n" + Traceback(e));
  }
  module.attr("_loading") = py::none();
  int added = 0;
  for (const auto& [name, entry] : features) {
    const py::tuple tuple = entry.cast<py::tuple>();
    if (tuple[2].cast<std::string>() != origin) continue;
    AddToRegistry(py::str(name).cast<std::string>(), tuple, registry);
    ++added;
  }
  if (added == 0) {
    throw ConfigError(where + ": plugin " + path +
                      ": registered no feature (a Python plugin calls "
                      "attend.register_feature(name, cls))");
  }
}

void RegisterFeature(const std::string& name, const py::object& cls) {
  if (name.empty() || name.find_first_of(" \t\n.=") != std::string::npos) {
    throw ConfigError("register_feature: '" + name +
                      "' is not a feature name (no spaces, dots or '=')");
  }
  if (Builtins().Find(name) != nullptr) {
    throw ConfigError("register_feature: '" + name + "' is a built-in feature's name");
  }
  if (!py::hasattr(cls, "compute") || !PyCallable_Check(cls.attr("compute").ptr())) {
    throw ConfigError("register_feature: '" + name + "': the class has no compute(context)");
  }
  std::string summary = "a Python feature";
  if (py::hasattr(cls, "__doc__") && !cls.attr("__doc__").is_none()) {
    const std::string doc = py::str(cls.attr("__doc__")).cast<std::string>();
    const size_t start = doc.find_first_not_of(" \n\t");
    if (start != std::string::npos) summary = doc.substr(start, doc.find('\n', start) - start);
  }
  py::module_ module = Module();
  const py::object loading = module.attr("_loading");
  const std::string origin =
      loading.is_none()
          ? "python: " + py::str(cls.attr("__module__")).cast<std::string>()
          : loading.cast<std::string>();
  py::dict features = module.attr("_features");
  features[py::str(name)] = py::make_tuple(cls, summary, origin);
}

template <typename T>
py::array_t<T> Column(const std::vector<T>& values, size_t width = 1) {
  std::vector<py::ssize_t> shape = {static_cast<py::ssize_t>(values.size() / width)};
  if (width > 1) shape.push_back(static_cast<py::ssize_t>(width));
  py::array_t<T> array(shape);
  if (!values.empty()) std::memcpy(array.mutable_data(), values.data(), values.size() * sizeof(T));
  return array;
}

}  // namespace

py::dict SegmentationDict(const Segmentation& segmentation) {
  std::vector<int32_t> area, bbox, perimeter, boundaries;
  std::vector<float> colour, saturation, intensity;
  for (const RegionStats& region : segmentation.regions) {
    area.push_back(region.area);
    bbox.insert(bbox.end(),
                {region.bbox.x, region.bbox.y, region.bbox.width, region.bbox.height});
    colour.insert(colour.end(), {region.colour.sx, region.colour.sy, region.colour.v});
    saturation.push_back(region.saturation);
    intensity.push_back(region.intensity);
    perimeter.push_back(region.perimeter);
  }
  for (const RegionBoundary& boundary : segmentation.adjacency.boundaries) {
    boundaries.insert(boundaries.end(), {boundary.a, boundary.b, boundary.length});
  }
  py::dict regions;
  regions["area"] = Column(area);
  regions["bbox"] = Column(bbox, 4);
  regions["colour"] = Column(colour, 3);
  regions["saturation"] = Column(saturation);
  regions["intensity"] = Column(intensity);
  regions["perimeter"] = Column(perimeter);
  py::dict result;
  result["labels"] = MatArray(segmentation.labels, false);
  result["regions"] = regions;
  result["boundaries"] = Column(boundaries, 3);
  result["pyramid_levels"] = segmentation.pyramid_levels;
  return result;
}

void RegisterPythonFeatures(py::module_& m) {
  m.attr("_features") = py::dict();
  m.attr("_loading") = py::none();
  py::class_<ContextView, std::shared_ptr<ContextView>>(m, "FeatureContext")
      .def_property_readonly("frame_index",
                             [](const ContextView& c) { return c.context().frame_index(); })
      .def_property_readonly("stereo", [](const ContextView& c) { return c.context().stereo(); })
      .def_property_readonly("size",
                             [](const ContextView& c) {
                               const cv::Size size = c.context().size();
                               return py::make_tuple(size.width, size.height);
                             })
      .def_property_readonly("left",
                             [](const ContextView& c) { return MatArray(c.context().left(), false); })
      .def_property_readonly(
          "right", [](const ContextView& c) { return MatArray(c.context().right(), false); })
      .def_property_readonly("cylinder", &ContextView::Cylinder)
      .def_property_readonly("tsl", &ContextView::Tsl)
      .def_property_readonly("regions", &ContextView::Regions)
      .def_property_readonly("disparity", &ContextView::Disparity)
      .def_property_readonly("attention_regions",
                             [](const ContextView& c) {
                               py::list boxes;
                               for (const cv::Rect& r : c.context().AttentionRegions()) {
                                 boxes.append(py::make_tuple(r.x, r.y, r.width, r.height));
                               }
                               return boxes;
                             })
      .def("builtin", &ContextView::Builtin, py::arg("name"));

  m.def("_register_feature", &RegisterFeature);
  m.def("_load_plugin_file", [](const py::capsule& registry, const std::string& path,
                                const std::string& where) {
    LoadFile(path, where, static_cast<FeatureRegistry*>(registry.get_pointer()));
  });
  PythonFeatureHooks hooks;
  hooks.load_file = &LoadFile;
  hooks.add_registered = &AddRegistered;
  SetPythonFeatureHooks(hooks);
}

}  // namespace attend::python
