#include "features/feature_set.h"

#include "util/shared_mat.h"

#include <exception>
#include <opencv2/core/utility.hpp>

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

void RunTasks(int count, bool concurrent, const std::function<void(int)>& task) {
  std::vector<std::exception_ptr> errors(count);
  auto run = [&](int i) {
    try {
      task(i);
    } catch (...) {
      errors[i] = std::current_exception();
    }
  };
  if (concurrent && count > 1) {
    cv::parallel_for_(
        cv::Range(0, count),
        [&](const cv::Range& range) {
          for (int i = range.start; i < range.end; ++i) run(i);
        },
        count);
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

void FeatureSet::Compute(const FrameContext& context, bool concurrent) {
  // A map of the last frame that someone still holds (a Python array) is let go, so that this
  // frame does not overwrite it (util/shared_mat.h).
  for (FeatureResult& result : results_) ReleaseIfShared(&result.map);
  RunTasks(static_cast<int>(members_.size()), concurrent, [&](int i) {
    const Stopwatch stopwatch;
    members_[i].feature->Compute(context, &results_[i].map);
    results_[i].milliseconds = stopwatch.ElapsedMs();
    CheckFeatureOutput(members_[i].entry, results_[i].map, context.size());
    results_[i].detections = members_[i].feature->detections();
    results_[i].searched_pixels = members_[i].feature->searched_pixels();
  });
}

}  // namespace attend
