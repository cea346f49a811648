#include "pipeline/options_io.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <filesystem>
#include <functional>

#include "config/param_block_yaml.h"
#include "config/read_fields.h"
#include "features/dnn_detector.h"
#include "util/error.h"
#include "util/strings.h"

namespace attend {

namespace {

// The sections of the configuration, a function each, in file order (VisitOptions below).
// Each binds the field tables (util/option_fields.h) of the options structs it holds; a
// table's order is the file's.

// sequence: the input and the frames taken.
template <typename Visitor>
void VisitSequence(AttendOptions* o, Visitor& v) {
  v.BeginSection("sequence");
  v.Fields(&o->sequence.source, SourceSpec::Fields());
  v.Fields(&o->sequence, SequenceOptions::Fields());
  v.EndSection([o] { return o->sequence.Check(); });
}

// live: how a live source (sequence.camera, sequence.gst) is read. Its check is the
// sequence's, which holds it, so that errors that join the two sections show here too.
template <typename Visitor>
void VisitLive(AttendOptions* o, Visitor& v) {
  v.BeginSection("live");
  v.Fields(&o->sequence.source.live, LiveOptions::Fields());
  v.EndSection([o] { return o->sequence.Check(); });
}

// segmentation: the BIP colour segmentation.
template <typename Visitor>
void VisitSegmentation(AttendOptions* o, Visitor& v) {
  v.BeginSection("segmentation");
  v.Fields(&o->segmentation, SegmentationOptions::Fields());
  v.Fields(&o->segmentation.bip, BipOptions::Fields());
  v.EndSection([o] { return o->segmentation.Check(); });
}

// output: the run folder's dumps and video.
template <typename Visitor>
void VisitOutput(AttendOptions* o, Visitor& v) {
  v.BeginSection("output");
  v.Fields(&o->output, OutputOptions::Fields());
  v.EndSection([o] { return o->output.Check(); });
}

// saliency: normalisation and combination of the feature maps.
template <typename Visitor>
void VisitSaliency(AttendOptions* o, Visitor& v) {
  v.BeginSection("saliency");
  v.Fields(&o->saliency, SaliencyOptions::Fields());
  // A plugin's normalisation is known once its library is loaded (FramePipeline); without
  // plugins the name must be a built-in one.
  const std::vector<std::string>& built_in = SaliencyOptions::Normalisations();
  const std::string& name = o->saliency.normalisation;
  v.Require(
      "normalisation",
      !o->plugins.empty() || std::find(built_in.begin(), built_in.end(), name) != built_in.end(),
      "'" + name + "' is not one of " + Join(built_in, ", ") + DidYouMean(name, built_in) +
          " (or a normalisation of a library in plugins)");
  v.EndSection([o] { return o->saliency.Check(); });
}

// select: the selection of new targets and their seeds; the skin rules' keys start "skin_".
template <typename Visitor>
void VisitSelect(AttendOptions* o, Visitor& v) {
  v.BeginSection("select");
  v.Fields(&o->attention.select, SelectOptions::Fields());
  v.Fields(&o->attention, AttentionOptions::Fields());
  v.Fields(&o->attention.skin_region, SkinRegionOptions::Fields(), "skin_");
  v.EndSection([o] { return o->attention.Check(); });
}

// drop: the release rules.
template <typename Visitor>
void VisitDrop(AttendOptions* o, Visitor& v) {
  v.BeginSection("drop");
  v.Fields(&o->attention.drop, DropOptions::Fields());
  v.EndSection([o] { return o->attention.Check(); });
}

// inhibition: inhibition of return.
template <typename Visitor>
void VisitInhibition(AttendOptions* o, Visitor& v) {
  v.BeginSection("inhibition");
  v.Fields(&o->attention.inhibition, InhibitionOptions::Fields());
  v.EndSection([o] { return o->attention.Check(); });
}

// attention: the object files.
template <typename Visitor>
void VisitMemory(AttendOptions* o, Visitor& v) {
  v.BeginSection("attention");
  v.Fields(&o->attention.memory, ObjectFileOptions::Fields());
  v.Fields(&o->attention.appearance, AppearanceOptions::Fields());
  v.EndSection([o] { return o->attention.Check(); });
}

// depth: each target's disparity and position in a stereo run, and depth in the loop.
template <typename Visitor>
void VisitDepth(AttendOptions* o, Visitor& v) {
  v.BeginSection("depth");
  v.Fields(&o->attention.depth, DepthOptions::Fields());
  v.EndSection([o] { return o->attention.Check(); });
}

// The tracker kinds that read `key` (TrackerKindInfo::uses_key), as "kcf or csrt".
std::string KindsUsing(std::string_view key) {
  std::vector<std::string> kinds;
  for (const TrackerKindInfo& info : TrackerKinds()) {
    if (info.uses_key(key)) kinds.emplace_back(info.name);
  }
  return Join(kinds, " or ");
}

// A key of another kind than the chosen one would have no effect: it is an error when its
// value differs from its default, so that a file that sets every key at its default (as
// configs/default.yaml and RUN/config.yaml do, SPEC 3.4) can change the kind alone.
template <typename Options, typename Visitor>
void CheckOwnedKeys(const Options& options, const Options& defaults,
                    const OptionFields<Options>& fields, const TrackerKindInfo& chosen,
                    Visitor& v) {
  for (const OptionField<Options>& field : fields) {
    if (!field.is_key || chosen.uses_key(field.name)) continue;
    if (SameFields(options, defaults, OptionFields<Options>{field})) continue;
    v.Owned(std::string(field.name), KindsUsing(field.name), chosen.name);
  }
}

// tracker: the kind, and each kind's own keys.
template <typename Visitor>
void VisitTracker(AttendOptions* o, Visitor& v) {
  v.BeginSection("tracker");
  TargetTrackerOptions& t = o->attention.tracker;
  v.Fields(&t, TargetTrackerOptions::Fields());
  ForEachTrackerOptionBlock([&](auto block, const auto& fields) { v.Fields(&(t.*block), fields); });
  if constexpr (Visitor::kChecks) {
    const TrackerKindInfo& chosen = TrackerKindOf(t.kind);
    const TargetTrackerOptions defaults;
    ForEachTrackerOptionBlock([&](auto block, const auto& fields) {
      CheckOwnedKeys(t.*block, defaults.*block, fields, chosen, v);
    });
  }
  v.EndSection([o] { return o->attention.Check(); });
}

// Visits every key of the configuration in file order. The visitor decides what a key means:
// read it from YAML, write it, list it or describe it. Keeping one list, made of the structs'
// field tables, is what keeps reading, writing and documentation in step.
template <typename Visitor>
void VisitOptions(AttendOptions* o, Visitor& v) {
  VisitSequence(o, v);
  VisitLive(o, v);
  VisitSegmentation(o, v);
  VisitOutput(o, v);
  v.Features("features", &o->features);
  v.Fields(o, AttendOptions::Fields(), "", "plugins");
  VisitSaliency(o, v);
  VisitSelect(o, v);
  VisitDrop(o, v);
  VisitInhibition(o, v);
  VisitMemory(o, v);
  VisitDepth(o, v);
  VisitTracker(o, v);
  v.Fields(o, AttendOptions::Fields(), "", "threads");
}

// The fields of `fields` to visit: all of them, or the one called `only`.
template <typename Options>
OptionFields<Options> Selected(const OptionFields<Options>& fields, std::string_view only) {
  if (only.empty()) return fields;
  return {FieldNamed(fields, only)};
}

// Reads keys from a ParamBlock, starting from the values already in the struct.
class Reader {
 public:
  static constexpr bool kChecks = true;
  explicit Reader(const ParamBlock& root) : blocks_{root} {}

  void BeginSection(const std::string& key) { blocks_.push_back(top().Child(key)); }
  void EndSection(const std::function<std::string()>& check) {
    const ParamBlock section = top();
    section.CheckNoUnknownKeys();
    const std::string error = check();
    if (!error.empty()) section.Fail("", error);
    blocks_.pop_back();
  }
  template <typename Options>
  void Fields(Options* options, const OptionFields<Options>& fields, const std::string& prefix = "",
              std::string_view only = {}) {
    ReadFields(top(), Selected(fields, only), options, prefix);
  }
  void Features(const std::string& key, std::vector<FeatureSpec>* specs) {
    *specs = ReadFeatureList(top(), key);
  }
  // A key that only some tracker kinds use, set away from its default while another kind is
  // chosen: an error naming its line.
  void Owned(const std::string& key, const std::string& owners, const std::string& chosen) {
    top().Fail(key, "is used only by tracker.kind " + owners + ", but tracker.kind is " + chosen +
                        " (" + top().Where("kind") + "); remove it or choose another kind");
  }
  // A condition on a key's value: false fails at the key's line.
  void Require(const std::string& key, bool holds, const std::string& message) {
    if (!holds) top().Fail(key, message);
  }
  void Finish() { top().CheckNoUnknownKeys(); }

 private:
  const ParamBlock& top() const { return blocks_.back(); }
  std::vector<ParamBlock> blocks_;
};

// Writes every key with its current value.
class Writer {
 public:
  static constexpr bool kChecks = false;
  Writer() { out_ << YAML::BeginMap; }
  void BeginSection(const std::string& key) {
    out_ << YAML::Key << key << YAML::Value << YAML::BeginMap;
  }
  void EndSection(const std::function<std::string()>&) { out_ << YAML::EndMap; }
  template <typename Options>
  void Fields(Options* options, const OptionFields<Options>& fields, const std::string& prefix = "",
              std::string_view only = {}) {
    ForEachField(Selected(fields, only),
                 [&](const OptionField<Options>& field, const auto& member) {
                   if (!field.is_key) return;
                   out_ << YAML::Key << prefix + std::string(field.name) << YAML::Value;
                   using M = std::remove_cvref_t<decltype(member)>;
                   if constexpr (std::is_member_object_pointer_v<M>) {
                     Emit(options->*member);
                   } else {
                     Emit(member.get(*options));
                   }
                 });
  }
  void Features(const std::string& key, std::vector<FeatureSpec>* specs) {
    out_ << YAML::Key << key << YAML::Value << YAML::BeginSeq;
    for (const FeatureSpec& spec : *specs) {
      // The plugin's own keys as given; name, weight (and enabled: false) first and with their
      // parsed values.
      out_ << YAML::Flow << YAML::BeginMap;
      out_ << YAML::Key << "name" << YAML::Value << spec.name;
      out_ << YAML::Key << "weight" << YAML::Value << spec.weight;
      if (!spec.enabled) out_ << YAML::Key << "enabled" << YAML::Value << false;
      const YAML::Node node = NodeOf(spec.params);
      for (auto it = node.begin(); it != node.end(); ++it) {
        const std::string name = it->first.Scalar();
        if (name == "name" || name == "weight" || name == "enabled") continue;
        out_ << YAML::Key << name << YAML::Value << it->second;
      }
      out_ << YAML::EndMap;
    }
    out_ << YAML::EndSeq;
  }
  void Require(const std::string&, bool, const std::string&) {}
  std::string Finish() {
    out_ << YAML::EndMap;
    return std::string(out_.c_str()) + "\n";
  }

 private:
  void Emit(const std::string& value) { out_ << YAML::DoubleQuoted << value; }
  void Emit(bool value) { out_ << YAML::TrueFalseBool << value; }
  void Emit(int value) { out_ << value; }
  void Emit(std::int64_t value) { out_ << value; }
  void Emit(std::uint64_t value) { out_ << value; }
  void Emit(double value) { out_ << value; }
  void Emit(float value) { out_ << static_cast<double>(value); }
  void Emit(const std::vector<double>& values) {
    out_ << YAML::Flow << YAML::BeginSeq;
    for (const double value : values) out_ << value;
    out_ << YAML::EndSeq;
  }
  void Emit(const std::vector<std::string>& values) {
    out_ << YAML::Flow << YAML::BeginSeq;
    for (const std::string& value : values) out_ << value;
    out_ << YAML::EndSeq;
  }

  YAML::Emitter out_;
};

// Describes the keys: dotted path, type, range, default and the field's line of doc.
class Describer {
 public:
  static constexpr bool kChecks = false;
  void BeginSection(const std::string& key) { prefix_.push_back(key); }
  void EndSection(const std::function<std::string()>&) { prefix_.pop_back(); }
  template <typename Options>
  void Fields(Options* options, const OptionFields<Options>& fields, const std::string& prefix = "",
              std::string_view only = {}) {
    OptionFields<Options> keys;
    for (const OptionField<Options>& field : Selected(fields, only)) {
      if (field.is_key) keys.push_back(field);
    }
    for (FieldDescription line : DescribeFields(keys, *options)) {
      line.key = Path(prefix + line.key);
      lines.push_back(line);
    }
  }
  void Features(const std::string& key, std::vector<FeatureSpec>*) {
    FieldDescription line;
    line.key = Path(key);
    line.type = "list of features";
    line.fallback = "colour_contrast, intensity_contrast, skin, disparity";
    line.doc = "feature maps with their weights and own keys (configs/README.md)";
    lines.push_back(line);
  }
  void Require(const std::string&, bool, const std::string&) {}
  std::vector<FieldDescription> lines;

 private:
  std::string Path(const std::string& key) const {
    std::vector<std::string> parts = prefix_;
    parts.push_back(key);
    return Join(parts, ".");
  }
  std::vector<std::string> prefix_;
};

}  // namespace

const OptionFields<OutputOptions>& OutputOptions::Fields() {
  using O = OutputOptions;
  static const OptionFields<OutputOptions> fields = {
      {"dir", &O::dir, "the run folder; \"\": runs/DATE-TIME-CONFIG-SEQUENCE"},
      {"dump", &O::dump, "per-frame dumps", &OutputOptions::DumpKinds},
      {"map_formats", &O::map_formats, "files written for each dumped map",
       &OutputOptions::MapFormats},
      {"video", &O::video, "also write the overlays as RUN/overlay.avi (needs overlay)"}};
  return fields;
}

const OptionFields<AttendOptions>& AttendOptions::Fields() {
  using O = AttendOptions;
  static const OptionFields<AttendOptions> fields = {
      {"plugins", &O::plugins, "out-of-tree plugin libraries loaded at start"},
      {"threads", &O::threads, Range::Closed(0, 256),
       "threads for the stages that share a frame's work; 0: one per core"}};
  return fields;
}

const std::vector<std::string>& OutputOptions::DumpKinds() {
  static const std::vector<std::string> kinds = {"overlay",    "regions",   "features",
                                                 "saliency",   "inhibition", "inhibited",
                                                 "background"};
  return kinds;
}

const std::vector<std::string>& OutputOptions::MapFormats() {
  static const std::vector<std::string> formats = {"pfm", "png"};
  return formats;
}

std::string OutputOptions::Check() const {
  for (const std::string& kind : dump) {
    if (std::count(dump.begin(), dump.end(), kind) > 1) return "dump lists '" + kind + "' twice";
  }
  for (const std::string& format : map_formats) {
    if (std::count(map_formats.begin(), map_formats.end(), format) > 1) {
      return "map_formats lists '" + format + "' twice";
    }
  }
  if (video && !Dumps("overlay")) return "video needs 'overlay' in dump";
  if ((Dumps("features") || Dumps("saliency") || Dumps("inhibition") || Dumps("inhibited")) &&
      map_formats.empty()) {
    return "map_formats is empty, so the map dumps would write nothing";
  }
  return "";
}

bool OutputOptions::Dumps(const std::string& kind) const {
  return std::find(dump.begin(), dump.end(), kind) != dump.end();
}

bool OutputOptions::WritesMapFormat(const std::string& format) const {
  return std::find(map_formats.begin(), map_formats.end(), format) != map_formats.end();
}

namespace {

// attention.appearance, a model file: found (features/dnn_detector.h, FindModelFile) and kept
// as an absolute path, so that RUN/config.yaml repeats the run from anywhere; a ConfigError at
// the key when it is nowhere.
void ResolveAppearanceModel(const ParamBlock& root, AppearanceOptions* appearance) {
  if (appearance->model.empty()) return;
  std::string places;
  const std::string found = FindModelFile(appearance->model, root.source(), "", &places);
  const ParamBlock attention = root.Child("attention");
  if (found.empty()) {
    attention.Fail("appearance",
                   "no such file: " + appearance->model +
                       (places.empty() ? "" : " (looked in " + places + ")") +
                       "; docs/MODELS.md says where to get each model (scripts/get_models.sh "
                       "DIR downloads them; then set ATTEND_MODELS=DIR)");
  }
  if (std::filesystem::is_directory(found)) {
    attention.Fail("appearance", found + ": is a folder, not a model file");
  }
  appearance->model = std::filesystem::absolute(found).lexically_normal().string();
}

}  // namespace

AttendOptions ReadOptions(const ParamBlock& root) {
  AttendOptions options;
  Reader reader(root);
  VisitOptions(&options, reader);
  reader.Finish();
  ResolveAppearanceModel(root, &options.attention.appearance);
  return options;
}

AttendOptions LoadOptions(const std::string& path, const std::vector<std::string>& overrides) {
  ParamBlock root = ParamBlock::LoadFile(path);
  for (const std::string& assignment : overrides) root.Override(assignment);
  return ReadOptions(root);
}

std::string OptionsToYaml(const AttendOptions& options) {
  AttendOptions copy = options;
  Writer writer;
  VisitOptions(&copy, writer);
  return writer.Finish();
}

std::vector<FieldDescription> DescribeConfiguration() {
  AttendOptions options;
  Describer describer;
  VisitOptions(&options, describer);
  return describer.lines;
}

std::vector<std::string> ConfigurationKeys() {
  std::vector<std::string> keys;
  for (const FieldDescription& line : DescribeConfiguration()) keys.push_back(line.key);
  return keys;
}

}  // namespace attend
