#include "pipeline/options_io.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <functional>

#include "config/param_block_yaml.h"
#include "util/error.h"
#include "util/strings.h"

namespace attend {

namespace {

// The sections of the configuration, a function each, in file order (VisitOptions below).

// sequence: the input and the frames taken.
template <typename Visitor>
void VisitSequence(AttendOptions* o, Visitor& v) {
  v.BeginSection("sequence");
  v.Ranges(&o->sequence, SequenceOptions::Ranges());
  v.Ranges(&o->sequence, SequenceOptions::SizeRanges());
  v.Field("folder", &o->sequence.folder);
  v.Field("left_video", &o->sequence.left_video);
  v.Field("right_video", &o->sequence.right_video);
  v.Field("side_by_side_video", &o->sequence.side_by_side_video);
  v.Field("video", &o->sequence.video);
  v.Field("images", &o->sequence.images);
  v.Field("first_frame", &o->sequence.first_frame);
  v.Field("last_frame", &o->sequence.last_frame);
  v.Field("stride", &o->sequence.stride);
  v.Field("width", &o->sequence.width);
  v.Field("height", &o->sequence.height);
  v.Choice("resize", &o->sequence.resize, SequenceOptions::ResizeModes());
  v.EndSection([o] { return o->sequence.Check(); });
}

// segmentation: the BIP colour segmentation.
template <typename Visitor>
void VisitSegmentation(AttendOptions* o, Visitor& v) {
  v.BeginSection("segmentation");
  v.Ranges(&o->segmentation, SegmentationOptions::Ranges());
  v.Field("t_max", &o->segmentation.t_max);
  v.Field("min_region_area", &o->segmentation.min_region_area);
  v.Field("link_across_kinds", &o->segmentation.bip.link_across_kinds);
  v.EndSection([o] { return o->segmentation.Check(); });
}

// output: the run folder's dumps and video.
template <typename Visitor>
void VisitOutput(AttendOptions* o, Visitor& v) {
  v.BeginSection("output");
  v.Field("dir", &o->output.dir);
  v.ChoiceList("dump", &o->output.dump, OutputOptions::DumpKinds());
  v.ChoiceList("map_formats", &o->output.map_formats, OutputOptions::MapFormats());
  v.Field("video", &o->output.video);
  v.EndSection([o] { return o->output.Check(); });
}

// saliency: normalisation and combination of the feature maps.
template <typename Visitor>
void VisitSaliency(AttendOptions* o, Visitor& v) {
  v.BeginSection("saliency");
  v.Ranges(&o->saliency, SaliencyOptions::Ranges());
  v.Choice("normalisation", &o->saliency.normalisation, SaliencyOptions::Normalisations());
  v.Field("local_maxima_window", &o->saliency.local_maxima_window);
  v.Field("blur", &o->saliency.blur);
  v.Choice("combination", &o->saliency.combination, {"sum", "product"});
  v.EndSection([o] { return o->saliency.Check(); });
}

// select: the selection of new targets and their seeds.
template <typename Visitor>
void VisitSelect(AttendOptions* o, Visitor& v) {
  v.BeginSection("select");
  v.Ranges(&o->attention.select, SelectOptions::Ranges());
  v.Ranges(&o->attention, AttentionOptions::Ranges());
  v.Ranges(&o->attention.skin_region, SkinRegionOptions::Ranges());
  v.Field("min_saliency", &o->attention.select.min_saliency);
  v.Field("min_area", &o->attention.select.min_area);
  v.Field("max_new", &o->attention.select.max_new);
  v.Field("max_targets", &o->attention.select.max_targets);
  v.Field("max_area_fraction", &o->attention.select.max_area_fraction);
  v.Field("max_inhibited_fraction", &o->attention.select.max_inhibited_fraction);
  v.Field("saliency_t_max", &o->attention.select.saliency_t_max);
  v.Choice("seed", &o->attention.select.seed, SelectOptions::Seeds());
  v.Field("seed_share", &o->attention.select.seed_share);
  v.Field("seed_level", &o->attention.select.seed_level);
  v.Field("detection_taken", &o->attention.select.detection_taken);
  v.Field("detected_only", &o->attention.select.detected_only);
  v.Field("reanchor_min_iou", &o->attention.select.reanchor_min_iou);
  v.Field("reanchor_max_iou", &o->attention.select.reanchor_max_iou);
  v.Field("reanchor_min_similarity", &o->attention.select.reanchor_min_similarity);
  v.Field("group_min_speed", &o->attention.select.group_min_speed);
  v.Field("group_flow_tolerance", &o->attention.select.group_flow_tolerance);
  v.Field("label_overlap", &o->attention.label_overlap);
  v.Field("skin_fraction", &o->attention.skin_fraction);
  v.Field("skin_model", &o->attention.skin_model);
  v.Field("skin_check", &o->attention.skin_check);
  v.Field("skin_confident", &o->attention.skin_region.confident);
  v.Field("skin_min_confident_share", &o->attention.skin_region.min_confident_share);
  v.Field("skin_max_mean_distance", &o->attention.skin_region.max_mean_distance);
  v.Field("skin_min_solidity", &o->attention.skin_region.min_solidity);
  v.Field("skin_max_aspect_ratio", &o->attention.skin_region.max_aspect_ratio);
  v.Field("skin_max_area_fraction", &o->attention.skin_region.max_area_fraction);
  v.Field("skin_min_area", &o->attention.skin_region.min_area);
  v.EndSection([o] { return o->attention.Check(); });
}

// drop: the release rules.
template <typename Visitor>
void VisitDrop(AttendOptions* o, Visitor& v) {
  v.BeginSection("drop");
  v.Ranges(&o->attention.drop, DropOptions::Ranges());
  v.Field("min_saliency", &o->attention.drop.min_saliency);
  v.Field("frames", &o->attention.drop.frames);
  v.Field("max_shared", &o->attention.drop.max_shared);
  v.Field("unrecognised_frames", &o->attention.drop.unrecognised_frames);
  v.EndSection([o] { return o->attention.Check(); });
}

// inhibition: inhibition of return.
template <typename Visitor>
void VisitInhibition(AttendOptions* o, Visitor& v) {
  v.BeginSection("inhibition");
  v.Ranges(&o->attention.inhibition, InhibitionOptions::Ranges());
  v.Field("margin", &o->attention.inhibition.margin);
  v.Field("keep_occluded", &o->attention.inhibition.keep_occluded);
  v.Field("occluded_search", &o->attention.inhibition.occluded_search);
  v.EndSection([o] { return o->attention.Check(); });
}

// attention: the object files.
template <typename Visitor>
void VisitMemory(AttendOptions* o, Visitor& v) {
  v.BeginSection("attention");
  v.Ranges(&o->attention.memory, ObjectFileOptions::Ranges());
  v.Field("memory_frames", &o->attention.memory.memory_frames);
  v.Field("memory_gate", &o->attention.memory.gate);
  v.Field("memory_max_size_ratio", &o->attention.memory.max_size_ratio);
  v.Field("memory_min_similarity", &o->attention.memory.min_similarity);
  v.Field("memory_velocity_decay", &o->attention.memory.velocity_decay);
  v.EndSection([o] { return o->attention.Check(); });
}

// The keys of the BIP tracker (kind bip; TrackerOptions) after `mode`, each once: `visit`
// is called with the key's name and its member.
template <typename Visit>
void ForEachBipKey(Visit&& visit) {
  visit("t_colour", &TrackerOptions::t_colour);
  visit("t_oversegment", &TrackerOptions::t_oversegment);
  visit("t_refine", &TrackerOptions::t_refine);
  visit("alpha", &TrackerOptions::alpha);
  visit("epsilon", &TrackerOptions::epsilon);
  visit("epsilon_max", &TrackerOptions::epsilon_max);
  visit("working_area", &TrackerOptions::working_area);
  visit("min_overlap", &TrackerOptions::min_overlap);
  visit("bounded_min_overlap", &TrackerOptions::bounded_min_overlap);
  visit("bound_growth", &TrackerOptions::bound_growth);
  visit("size_rate", &TrackerOptions::size_rate);
  visit("centre_rate", &TrackerOptions::centre_rate);
  visit("distinctive_weights", &TrackerOptions::distinctive_weights);
  visit("distinct_rate", &TrackerOptions::distinct_rate);
  visit("motion_sigma", &TrackerOptions::motion_sigma);
  visit("appearance", &TrackerOptions::appearance);
  visit("appearance_share", &TrackerOptions::appearance_share);
  visit("appearance_rate", &TrackerOptions::appearance_rate);
  visit("min_score", &TrackerOptions::min_score);
  visit("redetect_range", &TrackerOptions::redetect_range);
  visit("redetect_ratio", &TrackerOptions::redetect_ratio);
}

// tracker: the kind, and each kind's own keys.
template <typename Visitor>
void VisitTracker(AttendOptions* o, Visitor& v) {
  v.BeginSection("tracker");
  v.Ranges(&o->attention.tracker.bip, TrackerOptions::Ranges());
  v.Ranges(&o->attention.tracker.opencv, OpenCvTrackerOptions::Ranges());
  // Enums in the options; the visitors see their names.
  TargetTrackerOptions& t = o->attention.tracker;
  std::string kind = TrackerKindName(t.kind);
  v.Choice("kind", &kind, TrackerKindNames());
  TrackerKindFromName(kind, &t.kind);
  std::string mode = TrackerModeName(t.bip.mode);
  v.Choice("mode", &mode, TrackerModeNames());
  TrackerModeFromName(mode, &t.bip.mode);
  ForEachBipKey([&](const char* key, auto member) { v.Field(key, &(t.bip.*member)); });
  v.Field("lost_frames", &t.opencv.lost_frames);
  v.Field("kcf_detect_thresh", &t.opencv.kcf_detect_thresh);
  // A key of another kind than the chosen one would have no effect: it is an error when its
  // value differs from its default, so that a file that sets every key at its default (as
  // configs/default.yaml and RUN/config.yaml do, SPEC 3.4) can change the kind alone.
  const TargetTrackerOptions d;
  const bool bip = t.kind == TrackerKind::kBip;
  const std::string bip_kinds = "bip", opencv_kinds = "kcf or csrt";
  v.Owned("mode", bip, t.bip.mode == d.bip.mode, bip_kinds, kind);
  ForEachBipKey([&](const char* key, auto member) {
    v.Owned(key, bip, t.bip.*member == d.bip.*member, bip_kinds, kind);
  });
  v.Owned("lost_frames", !bip, t.opencv.lost_frames == d.opencv.lost_frames, opencv_kinds, kind);
  v.Owned("kcf_detect_thresh", t.kind == TrackerKind::kKcf,
          t.opencv.kcf_detect_thresh == d.opencv.kcf_detect_thresh, "kcf", kind);
  v.EndSection([o] { return o->attention.Check(); });
}

// Visits every key of the configuration in file order. The visitor decides what a key means:
// read it from YAML, write it, or list it. Keeping one list is what keeps reading, writing
// and documentation in step. The ranges of numeric keys are not written here: each section
// names the options structs whose fields it binds (Ranges), and a key takes the range of its
// field (util/field_ranges.h), the one that struct's Check() applies.
template <typename Visitor>
void VisitOptions(AttendOptions* o, Visitor& v) {
  VisitSequence(o, v);
  VisitSegmentation(o, v);
  VisitOutput(o, v);
  v.Features("features", &o->features);
  v.Field("plugins", &o->plugins);
  VisitSaliency(o, v);
  VisitSelect(o, v);
  VisitDrop(o, v);
  VisitInhibition(o, v);
  VisitMemory(o, v);
  VisitTracker(o, v);
  v.Field("threads", &o->threads, Range::Closed(0, 256));
}

// Reads keys from a ParamBlock, starting from the values already in the struct.
class Reader {
 public:
  explicit Reader(const ParamBlock& root) : blocks_{root} {}

  void BeginSection(const std::string& key) { blocks_.push_back(top().Child(key)); }
  void EndSection(const std::function<std::string()>& check) {
    const ParamBlock section = top();
    section.CheckNoUnknownKeys();
    const std::string error = check();
    if (!error.empty()) section.Fail("", error);
    blocks_.pop_back();
    ranges_.clear();
  }
  // The section's keys fill fields of `options`: each numeric one is read with its field's
  // range.
  template <typename Options>
  void Ranges(const Options* options, const FieldRanges<Options>& fields) {
    ranges_.push_back(
        [options, &fields](const void* field) { return FindFieldRange(*options, fields, field); });
  }
  void Field(const std::string& key, std::string* value) { *value = top().GetString(key, *value); }
  void Field(const std::string& key, bool* value) { *value = top().GetBool(key, *value); }
  void Field(const std::string& key, int* value, Range range = {}) {
    *value = top().GetInt(key, *value, RangeOf(value, range));
  }
  void Field(const std::string& key, double* value, Range range = {}) {
    *value = top().GetDouble(key, *value, RangeOf(value, range));
  }
  void Field(const std::string& key, float* value, Range range = {}) {
    *value = static_cast<float>(top().GetDouble(key, *value, RangeOf(value, range)));
  }
  void Field(const std::string& key, std::vector<std::string>* value) {
    *value = top().GetStrings(key, *value);
  }
  void Choice(const std::string& key, std::string* value, const std::vector<std::string>& choices) {
    *value = top().GetChoice(key, *value, choices);
  }
  void ChoiceList(const std::string& key, std::vector<std::string>* values,
                  const std::vector<std::string>& choices) {
    *values = top().GetStrings(key, *values);
    for (const std::string& value : *values) {
      if (std::find(choices.begin(), choices.end(), value) == choices.end()) {
        top().Fail(key, "'" + value + "' is not one of " + Join(choices, ", ") +
                            DidYouMean(value, choices));
      }
    }
  }
  void Features(const std::string& key, std::vector<FeatureSpec>* specs) {
    *specs = ReadFeatureList(top(), key);
  }
  // A key that only some choices of `choice_key` (here tracker.kind) use: set away from its
  // default while another is chosen, it is an error naming its line.
  void Owned(const std::string& key, bool belongs, bool is_default, const std::string& owners,
             const std::string& chosen) {
    if (belongs || is_default) return;
    top().Fail(key, "is used only by tracker.kind " + owners + ", but tracker.kind is " + chosen +
                        " (" + top().Where("kind") + "); remove it or choose another kind");
  }
  void Finish() { top().CheckNoUnknownKeys(); }

 private:
  const ParamBlock& top() const { return blocks_.back(); }
  // The range of the field at `field` in the structs the section named, else `given`.
  Range RangeOf(const void* field, const Range& given) const {
    for (const auto& find : ranges_) {
      if (const Range* range = find(field)) return *range;
    }
    return given;
  }
  std::vector<ParamBlock> blocks_;
  std::vector<std::function<const Range*(const void*)>> ranges_;
};

// Writes every key with its current value.
class Writer {
 public:
  Writer() { out_ << YAML::BeginMap; }
  void BeginSection(const std::string& key) {
    out_ << YAML::Key << key << YAML::Value << YAML::BeginMap;
  }
  void EndSection(const std::function<std::string()>&) { out_ << YAML::EndMap; }
  template <typename Options>
  void Ranges(const Options*, const FieldRanges<Options>&) {}
  template <typename T>
  void Field(const std::string& key, T* value, Range = {}) {
    out_ << YAML::Key << key << YAML::Value;
    Emit(*value);
  }
  void Choice(const std::string& key, std::string* value, const std::vector<std::string>&) {
    Field(key, value);
  }
  void ChoiceList(const std::string& key, std::vector<std::string>* values,
                  const std::vector<std::string>&) {
    Field(key, values);
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
  void Owned(const std::string&, bool, bool, const std::string&, const std::string&) {}
  std::string Finish() {
    out_ << YAML::EndMap;
    return std::string(out_.c_str()) + "\n";
  }

 private:
  void Emit(const std::string& value) { out_ << YAML::DoubleQuoted << value; }
  void Emit(bool value) { out_ << YAML::TrueFalseBool << value; }
  void Emit(int value) { out_ << value; }
  void Emit(double value) { out_ << value; }
  void Emit(float value) { out_ << static_cast<double>(value); }
  void Emit(const std::vector<std::string>& values) {
    out_ << YAML::Flow << YAML::BeginSeq;
    for (const std::string& value : values) out_ << value;
    out_ << YAML::EndSeq;
  }

  YAML::Emitter out_;
};

// Lists the dotted key paths.
class KeyLister {
 public:
  void BeginSection(const std::string& key) { prefix_.push_back(key); }
  void EndSection(const std::function<std::string()>&) { prefix_.pop_back(); }
  template <typename Options>
  void Ranges(const Options*, const FieldRanges<Options>&) {}
  template <typename T>
  void Field(const std::string& key, T*, Range = {}) {
    Add(key);
  }
  void Choice(const std::string& key, std::string*, const std::vector<std::string>&) { Add(key); }
  void ChoiceList(const std::string& key, std::vector<std::string>*,
                  const std::vector<std::string>&) {
    Add(key);
  }
  void Features(const std::string& key, std::vector<FeatureSpec>*) { Add(key); }
  void Owned(const std::string&, bool, bool, const std::string&, const std::string&) {}
  std::vector<std::string> keys;

 private:
  void Add(const std::string& key) {
    std::vector<std::string> parts = prefix_;
    parts.push_back(key);
    keys.push_back(Join(parts, "."));
  }
  std::vector<std::string> prefix_;
};

}  // namespace

const std::vector<std::string>& OutputOptions::DumpKinds() {
  static const std::vector<std::string> kinds = {"overlay",  "regions",    "features",
                                                 "saliency", "inhibition", "inhibited"};
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

AttendOptions ReadOptions(const ParamBlock& root) {
  AttendOptions options;
  Reader reader(root);
  VisitOptions(&options, reader);
  reader.Finish();
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

std::vector<std::string> ConfigurationKeys() {
  AttendOptions options;
  KeyLister lister;
  VisitOptions(&options, lister);
  return lister.keys;
}

}  // namespace attend
