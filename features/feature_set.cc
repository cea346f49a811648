#include "features/feature_set.h"

#include "util/shared_mat.h"

#include <exception>

#include "util/error.h"
#include "util/timer.h"

namespace attend {

struct FeatureSet::Member {
  FeatureRegistry::Entry entry;  // a copy: the set may outlive the registry
  std::unique_ptr<FeatureMap> feature;
};

FeatureSet::FeatureSet(const std::vector<FeatureSpec>& specs, const FeatureRegistry& registry,
                       const FeatureSetup& setup) {
  for (const FeatureSpec& spec : specs) {
    std::unique_ptr<FeatureMap> feature = registry.Create(spec, setup);
    if (!spec.enabled) continue;
    if (feature->NeedsStereo() && !setup.stereo) {
      spec.params.Fail("name", "feature '" + spec.name +
                                   "' needs a stereo sequence, and this one is monocular (set "
                                   "features." +
                                   spec.name + ".enabled=false)");
    }
    members_.push_back({*registry.Find(spec.name), std::move(feature)});
    results_.push_back({spec.name, spec.weight, spec.normalisation, cv::Mat(), 0.0, {}});
  }
}

FeatureSet::~FeatureSet() = default;

void RunTasks(ThreadPool* pool, int count, const std::function<void(int)>& task) {
  std::vector<std::exception_ptr> errors(count);
  auto run = [&](int i) {
    try {
      task(i);
    } catch (...) {
      errors[i] = std::current_exception();
    }
  };
  if (pool != nullptr) {
    pool->ParallelFor(count, run);
  } else {
    for (int i = 0; i < count; ++i) run(i);
  }
  for (const std::exception_ptr& error : errors) {
    if (error) std::rethrow_exception(error);
  }
}

void FeatureSet::BeginSequence(const SequenceStart& start) {
  for (Member& member : members_) member.feature->BeginSequence(start);
}

void FeatureSet::EndSequence() {
  for (Member& member : members_) member.feature->EndSequence();
}

void FeatureSet::Compute(const FrameContext& context, ThreadPool* pool) {
  Compute(context, pool, FeaturePhase::kAll, &results_);
}

std::vector<FeatureResult> FeatureSet::NewResults() const {
  std::vector<FeatureResult> results = results_;
  for (FeatureResult& result : results) {
    result.map = cv::Mat();
    result.milliseconds = 0.0;
    result.detections.clear();
    result.searched_pixels = -1.0;
  }
  return results;
}

bool FeatureSet::ReadsAttentionRegions() const {
  for (const Member& member : members_) {
    if (member.feature->ReadsAttentionRegions()) return true;
  }
  return false;
}

void FeatureSet::Compute(const FrameContext& context, ThreadPool* pool, FeaturePhase phase,
                         std::vector<FeatureResult>* results) {
  ATTEND_CHECK(results->size() == members_.size()) << "results must come from NewResults()";
  std::vector<int> chosen;
  for (size_t i = 0; i < members_.size(); ++i) {
    const bool reads = members_[i].feature->ReadsAttentionRegions();
    if (phase == FeaturePhase::kAll || (phase == FeaturePhase::kAfterAttention) == reads) {
      chosen.push_back(static_cast<int>(i));
    }
  }
  // A map of the last frame that someone still holds (a Python array) is let go, so that this
  // frame does not overwrite it (util/shared_mat.h).
  for (const int i : chosen) ReleaseIfShared(&(*results)[i].map);
  RunTasks(chosen.size() > 1 ? pool : nullptr, static_cast<int>(chosen.size()), [&](int k) {
    const int i = chosen[k];
    FeatureResult& result = (*results)[i];
    const Stopwatch stopwatch;
    members_[i].feature->Compute(context, &result.map);
    result.milliseconds = stopwatch.ElapsedMs();
    CheckFeatureOutput(members_[i].entry, result.map, context.size());
    result.detections = members_[i].feature->detections();
    result.searched_pixels = members_[i].feature->searched_pixels();
  });
}

}  // namespace attend
