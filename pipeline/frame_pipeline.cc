#include "pipeline/frame_pipeline.h"

#include <algorithm>
#include <cmath>

#include "colour/grey.h"
#include "features/builtin.h"
#include "features/disparity_feature.h"
#include "features/plugin_loader.h"
#include "io/skin_files.h"
#include "saliency/saliency.h"
#include "util/error.h"
#include "util/strings.h"
#include "util/timer.h"

namespace attend {

FeatureRegistry LoadFeatureRegistry(const std::vector<std::string>& plugins) {
  FeatureRegistry registry = BuiltinFeatures();
  for (size_t i = 0; i < plugins.size(); ++i) {
    LoadFeaturePlugin(plugins[i], "plugins." + std::to_string(i), &registry);
  }
  return registry;
}

namespace {

// The skin model of the attention stage, found as the skin feature finds its model.
SkinModel LoadAttentionSkinModel(const std::string& path, const FeatureSetup& setup) {
  const std::string found = setup.FindPath(path);
  if (found.empty()) {
    throw ConfigError("select.skin_model: no such file: " + path + " (looked in " +
                      setup.PlacesSearched() + ")");
  }
  try {
    return LoadSkinModel(found);
  } catch (const ConfigError& e) {
    throw ConfigError(std::string("select.skin_model: ") + e.what());
  }
}

// A plugin's normalisation must give CV_32FC1 of the map's size with values in [0, 1]; anything
// else is a configuration error naming the feature and the library (a broken plugin was
// configured), as for a feature's own map (CheckFeatureOutput).
void CheckNormalisedMap(const std::string& feature, const std::string& origin,
                        const cv::Mat& normalised, cv::Size size) {
  const std::string who = "the normalisation of feature '" + feature + "' (" + origin + ")";
  if (normalised.type() != CV_32FC1 || normalised.size() != size) {
    throw ConfigError(who + " returned a map that is not CV_32FC1 of the feature map's size");
  }
  if (!cv::checkRange(normalised, true, nullptr, 0.0, std::nextafter(1.0, 2.0))) {
    throw ConfigError(who + " returned values outside [0, 1] or not finite");
  }
}

}  // namespace

FramePipeline::FramePipeline(const AttendOptions& options, const FeatureRegistry& registry,
                             const FeatureSetup& setup)
    : options_(options),
      context_(options.segmentation),
      features_(options.features, registry, setup),
      attention_(options.attention, LoadAttentionSkinModel(options.attention.skin_model, setup)) {
  // The run's disparity (FrameContext::disparity_options) is the `disparity` feature's.
  for (const FeatureSpec& spec : options.features) {
    if (spec.enabled && spec.name == "disparity") {
      context_.set_disparity_options(ReadDisparityOptions(spec.params));
    }
  }
  normalised_.resize(features_.results().size());
  for (const FeatureResult& result : features_.results()) weights_.push_back(result.weight);
  // Each feature's normalisation: the built-in ones by name, then the registry's (plugins').
  const std::vector<std::string>& builtin = SaliencyOptions::Normalisations();
  std::vector<std::string> known = builtin;
  for (const std::string& name : registry.NormalisationNames()) {
    if (std::find(builtin.begin(), builtin.end(), name) != builtin.end()) {
      throw ConfigError(registry.FindNormalisation(name)->origin + ": registers normalisation '" +
                        name + "', which is built in");
    }
    known.push_back(name);
  }
  for (const FeatureSpec& spec : options.features) {
    if (!spec.enabled) continue;
    const std::string& name = spec.normalisation;
    ChosenNormalisation chosen_normalisation;
    MapNormalisation& normalise = chosen_normalisation.normalise;
    if (std::find(builtin.begin(), builtin.end(), name) != builtin.end()) {
      SaliencyOptions chosen = options.saliency;
      chosen.normalisation = name;
      normalise = [chosen](const cv::Mat& map, cv::Mat* out) { NormaliseMap(map, chosen, out); };
    } else if (!name.empty()) {
      const FeatureRegistry::NormalisationEntry* entry = registry.FindNormalisation(name);
      if (entry == nullptr) {
        spec.params.Fail("normalisation", "unknown normalisation '" + name + "'" +
                                              DidYouMean(name, known) +
                                              "; known: " + Join(known, ", "));
      }
      normalise = entry->normalise;
      chosen_normalisation.plugin = entry->origin;
    }
    normalisers_.push_back(std::move(chosen_normalisation));
  }
}

void FramePipeline::Process(const StereoFrame& frame, FrameRecord* record) {
  context_.Reset(frame.index, frame.left, frame.right);
  // Where attention looked in the previous frame is where gated top-down channels look now.
  context_.set_attention_regions(attention_.look_regions());

  Stopwatch stage;
  context_.Regions();
  record->timings.Add("segment", stage.ElapsedMs());

  // Existing targets first, so that their saliency is inhibited in this frame (SPEC 1). The
  // features do not depend on the targets, so with more than one thread the two run side by
  // side; both only read the frame context. Errors are rethrown in a fixed order.
  stage.Restart();
  if (options_.threads == 1) {
    attention_.Track(frame.left, context_.SkinDistance(attention_.skin_model()), &tracked_,
                     context_.Cylinder());
    stage.Restart();
    features_.Compute(context_, false);
  } else {
    RunTasks(2, true, [&](int task) {
      if (task == 0) {
        attention_.Track(frame.left, context_.SkinDistance(attention_.skin_model()), &tracked_,
                         context_.Cylinder());
      } else {
        features_.Compute(context_, true);
      }
    });
  }
  record->timings.Add("features", stage.ElapsedMs());
  for (const FeatureResult& result : features_.results()) {
    record->timings.Add("feature." + result.name, result.milliseconds);
  }

  stage.Restart();
  Saliency(frame);
  record->timings.Add("saliency", stage.ElapsedMs());

  detections_.clear();
  for (const FeatureResult& result : features_.results()) {
    detections_.insert(detections_.end(), result.detections.begin(), result.detections.end());
  }
  attention_.Select(frame.left, context_.SkinDistance(attention_.skin_model()), tracked_, saliency_,
                    context_.Regions(), &attended_, detections_);
  record->timings.Add("track", attended_.track_ms);
  record->timings.Add("inhibit", attended_.inhibit_ms);
  record->timings.Add("select", attended_.select_ms);
  record->inhibited_fraction = attended_.inhibited_fraction;
  RecordTargets(record);
}

void FramePipeline::Saliency(const StereoFrame& frame) {
  const std::vector<FeatureResult>& results = features_.results();
  for (size_t i = 0; i < results.size(); ++i) {
    const ChosenNormalisation& chosen = normalisers_[i];
    if (!chosen.normalise) {
      NormaliseMap(results[i].map, options_.saliency, &normalised_[i]);
      continue;
    }
    chosen.normalise(results[i].map, &normalised_[i]);
    if (!chosen.plugin.empty()) {
      CheckNormalisedMap(results[i].name, chosen.plugin, normalised_[i], results[i].map.size());
    }
  }
  // SPEC 2.3 divides by the sum of all weights. A grey frame has no colour, so there colour
  // features measure nothing rather than "no contrast"; counting their weights would cap the
  // saliency of grey input at the share of the other features, below select.min_saliency for
  // a plainly bright object (docs/ATTENTION.md, "Real and grey input"). Colour frames keep the
  // weights as configured.
  grey_ = IsGreyImage(frame.left);
  frame_weights_ = weights_;
  if (grey_) {
    for (size_t i = 0; i < results.size(); ++i) {
      double low = 0.0, high = 0.0;
      cv::minMaxLoc(results[i].map, &low, &high);
      if (!(high > low)) frame_weights_[i] = 0.0;
    }
  }
  if (options_.saliency.combination == "product") {
    MultiplyMaps(normalised_, frame_weights_, context_.size(), &saliency_);
  } else {
    CombineMaps(normalised_, frame_weights_, context_.size(), &saliency_);
  }
  SmoothSaliency(options_.saliency, &saliency_);
}

void FramePipeline::RecordTargets(FrameRecord* record) const {
  record->targets.clear();
  for (const AttendedTarget& target : attended_.targets) {
    TargetRecord out;
    out.id = target.id;
    out.bbox = target.box;
    out.area = target.area;
    out.saliency = target.saliency;
    out.state = target.state;
    out.kind = target.skin ? "skin" : "object";
    const bool bip = options_.attention.tracker.kind == TrackerKind::kBip;
    out.similarity = !bip ? "appearance" : target.skin ? "skin" : "hsv";
    out.tracker = attention_.tracker_name();
    out.reason = target.reason;
    out.absent_frames = target.absent_frames;
    out.label = target.label;
    record->targets.push_back(out);
  }
  record->new_ids = attended_.new_ids;
}

}  // namespace attend
