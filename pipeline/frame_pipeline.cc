#include "pipeline/frame_pipeline.h"

#include <algorithm>
#include <cmath>

#include "colour/grey.h"
#include "features/builtin.h"
#include "features/disparity_feature.h"
#include "features/plugin_loader.h"
#include "features/python_plugins.h"
#include "io/skin_files.h"
#include "saliency/saliency_stage.h"
#include "util/error.h"
#include "util/strings.h"
#include "util/timer.h"

namespace attend {

FeatureRegistry LoadFeatureRegistry(const std::vector<std::string>& plugins) {
  FeatureRegistry registry = BuiltinFeatures();
  AddPythonFeatures(&registry);
  for (size_t i = 0; i < plugins.size(); ++i) {
    LoadFeaturePlugin(plugins[i], "plugins." + std::to_string(i), &registry);
  }
  return registry;
}

std::vector<std::string> LeaveOutStereoFeatures(const FeatureRegistry& registry,
                                                FeatureSetup setup,
                                                std::vector<FeatureSpec>* features) {
  setup.stereo = true;  // to ask each feature whether it needs stereo
  std::vector<std::string> left_out;
  for (FeatureSpec& spec : *features) {
    if (!spec.enabled) continue;
    if (registry.Create(spec, setup)->NeedsStereo()) {
      spec.enabled = false;
      left_out.push_back(spec.name);
    }
  }
  return left_out;
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

// The normalisation called `name` (`where` names the key for messages); `fail` reports an
// unknown name.
template <typename Fail>
const NormalisationRegistry::Entry* FindNormalisation(const NormalisationRegistry& registry,
                                                      const std::string& name, Fail&& fail) {
  const NormalisationRegistry::Entry* entry = registry.Find(name);
  if (entry == nullptr) {
    const std::vector<std::string> known = registry.Names();
    fail("unknown normalisation '" + name + "'" + DidYouMean(name, known) +
         "; known: " + Join(known, ", "));
  }
  return entry;
}

// The saliency stage of the enabled features, each with its normalisation.
SaliencyStage MakeSaliencyStage(const AttendOptions& options, const FeatureRegistry& registry) {
  const NormalisationRegistry& normalisations = registry.normalisations();
  const NormalisationRegistry::Entry* fallback = FindNormalisation(
      normalisations, options.saliency.normalisation, [](const std::string& message) {
        throw ConfigError("saliency.normalisation: " + message);
      });
  std::vector<SaliencyInput> inputs;
  for (const FeatureSpec& spec : options.features) {
    if (!spec.enabled) continue;
    SaliencyInput input;
    input.name = spec.name;
    input.weight = spec.weight;
    input.additive = spec.additive;
    if (!spec.normalisation.empty()) {
      input.normalisation = *FindNormalisation(
          normalisations, spec.normalisation,
          [&spec](const std::string& message) { spec.params.Fail("normalisation", message); });
    }
    inputs.push_back(input);
  }
  return SaliencyStage(options.saliency, *fallback, std::move(inputs));
}

}  // namespace

FramePipeline::Slot::Slot(const SegmentationOptions& segmentation, BipPool* pool,
                          std::shared_ptr<DisparityEstimators> estimators,
                          const DisparityOptions& disparity, std::vector<FeatureResult> features)
    : context(segmentation, pool, std::move(estimators)), features(std::move(features)) {
  context.set_disparity_options(disparity);
}

FramePipeline::FramePipeline(const AttendOptions& options, const FeatureRegistry& registry,
                             const FeatureSetup& setup, ExecutionContext* execution)
    : options_(options),
      execution_(execution),
      threads_(execution->threads()),
      features_(options.features, registry, setup),
      saliency_(MakeSaliencyStage(options, registry)),
      has_late_features_(features_.ReadsAttentionRegions()),
      attention_(options.attention, LoadAttentionSkinModel(options.attention.skin_model, setup),
                 execution->Shared<BipPool>()) {
  // The run's disparity (FrameContext::disparity_options) is the `disparity` feature's.
  for (const FeatureSpec& spec : options.features) {
    if (spec.enabled && spec.name == "disparity") {
      has_disparity_ = true;
      disparity_options_ = ReadDisparityOptions(spec.params);
    }
  }
  slots_[0] = std::make_unique<Slot>(options_.segmentation, execution_->Shared<BipPool>(),
                                     estimators_, disparity_options_,
                                     features_.NewResults());
}

FramePipeline::Slot& FramePipeline::Begin(int index, const StereoFrame& frame) {
  Slot& slot = *slots_[index];
  slot.frame = frame;
  slot.context.Reset(frame.index, frame.left, frame.right);
  slot.timings = StageTimes();
  return slot;
}

void FramePipeline::ComputeFeatures(Slot* slot, FeaturePhase phase, ThreadPool* pool) {
  const Stopwatch stage;
  features_.Compute(slot->context, pool, phase, &slot->features);
  slot->timings.Add("features", stage.ElapsedMs());
}

void FramePipeline::Process(const StereoFrame& frame, FrameRecord* record) {
  ATTEND_CHECK(pending_.load() == 0)
      << "Process cannot run while a frame given to Ahead waits for Finish";
  if (slots_[1] != nullptr) current_ = 1 - current_;
  ahead_slot_ = 1 - current_;
  Slot& slot = Begin(current_, frame);
  // Where attention looked in the previous frame is where gated top-down channels look now.
  slot.context.set_attention_regions(attention_.look_regions());

  Stopwatch stage;
  slot.context.Regions();
  record->timings.Add("segment", stage.ElapsedMs());

  // Existing targets first, so that their saliency is inhibited in this frame (SPEC 1). The
  // features do not depend on the targets, so with more than one thread the two run side by
  // side; both only read the frame context. Errors are rethrown in a fixed order.
  stage.Restart();
  ThreadPool* pool = threads_ > 1 ? execution_->pool() : nullptr;
  if (pool == nullptr) {
    Track(slot);
    stage.Restart();
    features_.Compute(slot.context, nullptr, FeaturePhase::kAll, &slot.features);
  } else {
    RunTasks(pool, 2, [&](int task) {
      if (task == 0) {
        Track(slot);
      } else {
        features_.Compute(slot.context, pool, FeaturePhase::kAll, &slot.features);
      }
    });
  }
  record->timings.Add("features", stage.ElapsedMs());
  for (const FeatureResult& result : slot.features) {
    record->timings.Add("feature." + result.name, result.milliseconds);
  }

  stage.Restart();
  Saliency(&slot);
  record->timings.Add("saliency", stage.ElapsedMs());
  Select(slot, record);
}

void FramePipeline::Ahead(const StereoFrame& frame) {
  if (slots_[1] == nullptr) {
    slots_[1] = std::make_unique<Slot>(options_.segmentation, execution_->Shared<BipPool>(),
                                       estimators_, disparity_options_,
                                       features_.NewResults());
  }
  ATTEND_CHECK(pending_.fetch_add(1) <= 1) << "Ahead is at most one frame ahead of Finish";
  Slot& slot = Begin(ahead_slot_, frame);
  ahead_slot_ = 1 - ahead_slot_;
  Stopwatch stage;
  slot.context.Regions();
  slot.timings.Add("segment", stage.ElapsedMs());
  // The pool's other threads help only when there are more than two: this thread and the
  // caller's are busy with two frames.
  ThreadPool* pool = threads_ > 2 ? execution_->pool() : nullptr;
  ComputeFeatures(&slot, FeaturePhase::kAhead, pool);
}

void FramePipeline::Finish(FrameRecord* record) {
  ATTEND_CHECK(pending_.load() >= 1) << "Finish needs a frame given to Ahead";
  current_ = 1 - current_;
  Slot& slot = *slots_[current_];
  // The features that read where attention looked (a detector gated by attention, on its
  // crops) run beside the tracking, which does not depend on them: on the pool's thread once
  // it is done with the next frame's Ahead, else one after the other on this one.
  bool tracked = false;
  if (has_late_features_) {
    slot.context.set_attention_regions(attention_.look_regions());
    RunTasks(execution_->pool(), 2, [&](int task) {
      if (task == 0) {
        ComputeFeatures(&slot, FeaturePhase::kAfterAttention, nullptr);
      } else {
        Track(slot);
      }
    });
    tracked = true;
  }
  for (const auto& [name, ms] : slot.timings.stages()) record->timings.Add(name, ms);
  for (const FeatureResult& result : slot.features) {
    record->timings.Add("feature." + result.name, result.milliseconds);
  }
  const Stopwatch stage;
  Saliency(&slot);
  record->timings.Add("saliency", stage.ElapsedMs());
  if (!tracked) Track(slot);
  Select(slot, record);
  --pending_;
}

void FramePipeline::Track(const Slot& slot) {
  attention_.Track(slot.frame.left, slot.context.SkinDistance(attention_.skin_model()),
                   &tracked_, slot.context.Cylinder());
}

void FramePipeline::Select(const Slot& slot, FrameRecord* record) {
  detections_.clear();
  for (const FeatureResult& result : slot.features) {
    detections_.insert(detections_.end(), result.detections.begin(), result.detections.end());
  }
  attention_.Select(slot.frame.left, slot.context.SkinDistance(attention_.skin_model()),
                    tracked_, saliency_.saliency(), slot.context.Regions(), &attended_,
                    detections_, StereoOf(slot));
  record->timings.Add("track", attended_.track_ms);
  record->timings.Add("inhibit", attended_.inhibit_ms);
  record->timings.Add("select", attended_.select_ms);
  record->inhibited_fraction = attended_.inhibited_fraction;
  RecordTargets(record);
}

void FramePipeline::SetCamera(const SequenceInfo& info) {
  calibration_ = info.calibration;
  scale_x_ = info.scale_x;
  scale_y_ = info.scale_y;
  attention_.SetFrameRate(info.fps);
  attention_.SetBaseline(calibration_ != nullptr ? calibration_->baseline_m() : 0.0);
}

StereoInput FramePipeline::StereoOf(const Slot& slot) const {
  const DepthOptions& depth = options_.attention.depth;
  StereoInput stereo;
  if (slot.frame.right.empty()) return stereo;
  const DisparityOptions& disparity = slot.context.disparity_options();
  // The dense map is the disparity feature's: without that feature none is computed (method
  // map then measures by the template, and the background has no depth rules). The background
  // (select.background) reads it even where the targets' depth is off.
  if (has_disparity_) {
    stereo.disparity = slot.context.Disparity(disparity);
    stereo.measured = slot.context.DisparityMeasured(disparity);
    stereo.ground = slot.context.DisparityGround(disparity);
  }
  if (depth.method == TargetDisparityMethod::kOff) return stereo;
  stereo.right = slot.frame.right;
  stereo.max_disparity = disparity.max_disparity;
  stereo.window = disparity.window;
  return stereo;
}

void FramePipeline::Saliency(Slot* slot) {
  maps_.clear();
  for (const FeatureResult& result : slot->features) maps_.push_back(&result.map);
  grey_ = IsGreyImage(slot->frame.left);
  saliency_.Combine(maps_, grey_, slot->context.size());
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
    const TrackerKindInfo& kind = TrackerKindOf(options_.attention.tracker.kind);
    out.similarity = target.skin ? kind.skin_similarity : kind.colour_similarity;
    out.tracker = attention_.tracker_name();
    out.reason = target.reason;
    out.absent_frames = target.absent_frames;
    out.label = target.label;
    out.disparity_px = target.disparity;
    out.disparity_sd_px = target.disparity_sd;
    if (target.depth_unmeasured) out.depth_missing = "unmeasured";
    if (calibration_ != nullptr && target.centroid.x >= 0.f) {
      // The calibration's pixels are the native frame's (SPEC 3.3's input pixels).
      const cv::Point2d centroid((target.centroid.x + 0.5) / scale_x_ - 0.5,
                                 (target.centroid.y + 0.5) / scale_y_ - 0.5);
      const DisparityEstimate native{target.disparity / scale_x_, target.disparity_sd / scale_x_};
      Position3d position;
      if (Triangulate(calibration_->focal_px(), calibration_->cx(), calibration_->cy(),
                      calibration_->baseline_m(), centroid, native, &position)) {
        out.has_position = true;
        out.position_m = position.m;
        out.position_sd_m = position.sd_m;
      }
    }
    record->targets.push_back(out);
  }
  record->new_ids = attended_.new_ids;
}

}  // namespace attend
