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

// Runs task(0) .. task(count - 1), on OpenCV's thread pool when `concurrent`, else in order on
// this thread. An exception of a task is kept, and after all tasks have run the first one in
// index order is rethrown, so the error reported does not depend on scheduling.
void RunTasks(int count, bool concurrent, const std::function<void(int)>& task);

class FeatureSet {
 public:
  // Creates every listed feature, so that each one checks its parameters, and keeps the
  // enabled ones. Unknown names and bad parameters: ConfigError.
  FeatureSet(const std::vector<FeatureSpec>& specs, const FeatureRegistry& registry,
             const FeatureSetup& setup);
  ~FeatureSet();

  // Computes every enabled feature on `context`; with `concurrent`, on OpenCV's thread pool.
  // A plugin that throws, or returns a map of the wrong type or size, stops the frame with the
  // error of the first such plugin in list order.
  void Compute(const FrameContext& context, bool concurrent);
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
