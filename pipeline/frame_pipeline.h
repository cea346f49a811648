// The per-frame stages of SPEC 1 that turn a stereo frame into maps: the colour conversions and
// BIP segmentation (shared through the frame context), the feature plugins and the saliency
// map. `attend run` drives it frame by frame and writes what it produced.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "features/feature_map.h"
#include "features/feature_set.h"
#include "features/lazy_frame_context.h"
#include "io/frame_record.h"
#include "io/sequence.h"
#include "pipeline/attend_options.h"
#include "saliency/saliency_stage.h"
#include "semiattentive/attention.h"
#include "util/execution_context.h"

namespace attend {

// The built-in features, those registered from Python (attend.register_feature, when the
// attend Python module is loaded) and those of the plugins in `plugins`, libraries or Python
// files (ConfigError naming the plugin that cannot be used).
FeatureRegistry LoadFeatureRegistry(const std::vector<std::string>& plugins);

// Disables (enabled: false) every enabled feature of `features` that needs stereo
// (FeatureMap::NeedsStereo) and returns their names, in list order: `attend saliency` on still
// images, and `attend run` with the shipped configuration on a monocular source, leave them out
// instead of refusing the configuration. `setup` serves to create each plugin to ask it
// (ConfigError for a plugin that cannot be created).
std::vector<std::string> LeaveOutStereoFeatures(const FeatureRegistry& registry,
                                                FeatureSetup setup,
                                                std::vector<FeatureSpec>* features);

class FramePipeline {
 public:
  // Creates the feature plugins (ConfigError for unknown names or bad parameters). `execution`
  // (util/execution_context.h), the caller's, must outlive the pipeline: its threads say whether
  // the tracking runs beside the features, and its BipPool serves every pyramid of a frame.
  FramePipeline(const AttendOptions& options, const FeatureRegistry& registry,
                const FeatureSetup& setup, ExecutionContext* execution);

  // Runs the stages of SPEC 1 on `frame` and fills `record` (targets, new ids) and its times:
  // `segment` (colour conversion and BIP segmentation), `track` (the existing targets),
  // `features` (wall time of the plugins, and of the tracking too when it runs beside them on a
  // second thread), `feature.<name>` (each plugin's own time), `saliency`, `inhibit` and
  // `select`.
  void Process(const StereoFrame& frame, FrameRecord* record);
  // Tell the feature plugins that a sequence starts (before its first Process) or has ended.
  void BeginSequence(const SequenceStart& start) { features_.BeginSequence(start); }
  void EndSequence() { features_.EndSequence(); }
  // The sequence's camera: its stereo calibration (SequenceInfo::calibration; none: targets
  // get a disparity but no position) and the working size's scales, which take the targets'
  // centroids and disparities to the calibration's pixels.
  void SetCamera(const SequenceInfo& info);

  // Results of the last frame.
  const FrameContext& context() const { return context_; }
  const std::vector<FeatureResult>& features() const { return features_.results(); }
  // Each feature's map normalised to [0, 1], in the order of features().
  const std::vector<cv::Mat>& normalised() const { return saliency_.normalised(); }
  const cv::Mat& saliency() const { return saliency_.saliency(); }
  // Whether the last frame was grey (colour/grey.h): on a grey frame a feature whose map is
  // constant (colour contrast and skin, which are 0 there) gets weight 0 in its saliency, so
  // it does not dilute the features that see something.
  bool grey() const { return grey_; }
  const cv::Mat& inhibition() const { return attention_.inhibition(); }
  const cv::Mat& inhibited() const { return attention_.inhibited(); }
  int targets_attended() const { return attention_.targets_attended(); }
  // The maps above are overwritten by the next Process, unless someone else holds one (a
  // cv::Mat header of their own, a Python array): each stage then writes that map into a new
  // buffer and the holder keeps its values (util/shared_mat.h).

 private:
  // The feature maps normalised, weighted and combined by saliency_ (SPEC 2.3).
  void Saliency(const StereoFrame& frame);
  // What the attention stage takes of the stereo pair for the targets' disparities.
  StereoInput StereoOf(const StereoFrame& frame) const;
  // The attention stage's targets as the frame's records (SPEC 3.3).
  void RecordTargets(FrameRecord* record) const;

  const AttendOptions options_;
  const int threads_;  // the execution context's
  LazyFrameContext context_;
  FeatureSet features_;
  SaliencyStage saliency_;
  std::vector<const cv::Mat*> maps_;  // the features' maps, for saliency_
  bool grey_ = false;
  AttentionStage attention_;
  TrackedTargets tracked_;  // what attention_ tracked in this frame
  std::vector<Detection> detections_;  // the top-down channels' detections in this frame
  AttentionFrame attended_;
  bool has_disparity_ = false;  // the disparity feature is enabled
  std::shared_ptr<const StereoCalibration> calibration_;
  double scale_x_ = 1.0, scale_y_ = 1.0;
};

}  // namespace attend
