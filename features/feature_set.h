// The feature plugins of a run: created once from the `features:` list, then computed on every
// frame's context, concurrently when allowed. Each plugin writes only its own map, so the maps
// do not depend on the number of threads.
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "config/feature_list.h"
#include "features/feature_map.h"
#include "util/thread_pool.h"

namespace attend {

// One enabled feature and its map of the last frame.
struct FeatureResult {
  std::string name;
  double weight = 1.0;
  std::string normalisation;  // FeatureSpec::normalisation ("" for the default)
  cv::Mat map;                // CV_32FC1, the frame's size
  double milliseconds = 0.0;  // computing this map (including shared work it triggered first)
  std::vector<Detection> detections;  // a top-down channel's (FeatureMap::detections)
  double searched_pixels = -1.0;      // FeatureMap::searched_pixels
};

// Runs task(0) .. task(count - 1), on `pool`'s threads and this one (ThreadPool::ParallelFor),
// or in order on this thread when `pool` is nullptr. An exception of a task is kept, and after
// all tasks have run the first one in index order is rethrown, so the error reported does not
// depend on scheduling.
void RunTasks(ThreadPool* pool, int count, const std::function<void(int)>& task);

// Which of a set's features a call computes: all of them, or those that do not read where
// attention looked (FeatureMap::ReadsAttentionRegions), which may run before the attention
// stage has finished the frame before, or those that do.
enum class FeaturePhase { kAll, kAhead, kAfterAttention };

class FeatureSet {
 public:
  // Creates every listed feature, so that each one checks its parameters, and keeps the
  // enabled ones. Unknown names and bad parameters: ConfigError.
  FeatureSet(const std::vector<FeatureSpec>& specs, const FeatureRegistry& registry,
             const FeatureSetup& setup);
  ~FeatureSet();

  // Computes every enabled feature on `context` into results(); with a `pool`, on its threads.
  // A plugin that throws, or returns a map of the wrong type or size, stops the frame with the
  // error of the first such plugin in list order.
  void Compute(const FrameContext& context, ThreadPool* pool = nullptr);
  // The same for the features of `phase`, into `results` (from NewResults(); the entries of
  // the other features are left as they are). A caller that works on two frames at once keeps
  // a results vector for each, so that one frame's maps are not overwritten by the next's.
  void Compute(const FrameContext& context, ThreadPool* pool, FeaturePhase phase,
               std::vector<FeatureResult>* results);
  // Results with each feature's name, weight and normalisation and no map yet.
  std::vector<FeatureResult> NewResults() const;
  // Whether some feature reads AttentionRegions (FeaturePhase::kAfterAttention).
  bool ReadsAttentionRegions() const;
  // FeatureMap::BeginSequence and EndSequence of every enabled feature, in list order.
  void BeginSequence(const SequenceStart& start);
  void EndSequence();

  const std::vector<FeatureResult>& results() const { return results_; }

 private:
  struct Member;
  std::vector<Member> members_;
  std::vector<FeatureResult> results_;
};

}  // namespace attend
