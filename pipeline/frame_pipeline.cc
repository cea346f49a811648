#include "pipeline/frame_pipeline.h"

#include "features/builtin.h"
#include "features/plugin_loader.h"
#include "saliency/saliency.h"
#include "util/timer.h"

namespace attend {

FeatureRegistry LoadFeatureRegistry(const std::vector<std::string>& plugins) {
  FeatureRegistry registry = BuiltinFeatures();
  for (size_t i = 0; i < plugins.size(); ++i) {
    LoadFeaturePlugin(plugins[i], "plugins." + std::to_string(i), &registry);
  }
  return registry;
}

FramePipeline::FramePipeline(const AttendOptions& options, const FeatureRegistry& registry,
                             const FeatureSetup& setup)
    : options_(options),
      context_(options.segmentation),
      features_(options.features, registry, setup) {
  normalised_.resize(features_.results().size());
  for (const FeatureResult& result : features_.results()) weights_.push_back(result.weight);
}

void FramePipeline::Process(const StereoFrame& frame, FrameRecord* record) {
  context_.Reset(frame.index, frame.left, frame.right);

  Stopwatch stage;
  context_.Regions();
  record->timings.Add("segment", stage.ElapsedMs());

  stage.Restart();
  features_.Compute(context_, options_.threads != 1);
  record->timings.Add("features", stage.ElapsedMs());
  for (const FeatureResult& result : features_.results()) {
    record->timings.Add("feature." + result.name, result.milliseconds);
  }

  stage.Restart();
  const std::vector<FeatureResult>& results = features_.results();
  for (size_t i = 0; i < results.size(); ++i) {
    NormaliseMap(results[i].map, options_.saliency, &normalised_[i]);
  }
  CombineMaps(normalised_, weights_, context_.size(), &saliency_);
  record->timings.Add("saliency", stage.ElapsedMs());
}

}  // namespace attend
