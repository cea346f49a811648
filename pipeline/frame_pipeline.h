// The per-frame stages of SPEC 1 that turn a stereo frame into maps: the colour conversions and
// BIP segmentation (shared through the frame context), the feature plugins and the saliency
// map. `attend run` drives it frame by frame and writes what it produced.
#pragma once

#include <atomic>
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

  // The same stages split in two, for a caller that works on two frames at once (`attend run`
  // with two threads or more, pipeline/run.cc): Ahead(t + 1) may run on another thread while
  // Finish() completes frame t, and the records are those of Process.
  //
  // Ahead: the stages of `frame` that do not depend on the attention stage's work on the frame
  // before: the colour conversions and segmentation, the features that do not read where
  // attention looked (FeatureMap::ReadsAttentionRegions). Its images must outlive the Finish()
  // of this frame. Not beside another Ahead, and at most one frame ahead of Finish.
  void Ahead(const StereoFrame& frame);
  // The rest of the frame last given to Ahead, which becomes the frame of the accessors below:
  // the features that read where attention looked, the saliency, tracking, inhibition and
  // selection. Fills `record` as Process does (`segment`, `features` and `saliency` times
  // included); not beside another Finish.
  void Finish(FrameRecord* record);
  // Tell the feature plugins that a sequence starts (before its first Process) or has ended.
  void BeginSequence(const SequenceStart& start) { features_.BeginSequence(start); }
  void EndSequence() { features_.EndSequence(); }
  // The sequence's camera: its stereo calibration (SequenceInfo::calibration; none: targets
  // get a disparity but no position) and the working size's scales, which take the targets'
  // centroids and disparities to the calibration's pixels.
  void SetCamera(const SequenceInfo& info);

  // Results of the last frame.
  const FrameContext& context() const { return current().context; }
  const std::vector<FeatureResult>& features() const { return current().features; }
  // Each feature's map normalised to [0, 1], in the order of features().
  const std::vector<cv::Mat>& normalised() const { return saliency_.normalised(); }
  const cv::Mat& saliency() const { return saliency_.saliency(); }
  // Whether the last frame was grey (colour/grey.h): on a grey frame a feature whose map is
  // constant (colour contrast and skin, which are 0 there) gets weight 0 in its saliency, so
  // it does not dilute the features that see something.
  bool grey() const { return grey_; }
  const cv::Mat& inhibition() const { return attention_.inhibition(); }
  // Each pixel's BackgroundKind in the last frame (AttentionStage::background).
  const cv::Mat& background() const { return attention_.background(); }
  const cv::Mat& inhibited() const { return attention_.inhibited(); }
  int targets_attended() const { return attention_.targets_attended(); }
  // The maps above are overwritten by the next Process, unless someone else holds one (a
  // cv::Mat header of their own, a Python array): each stage then writes that map into a new
  // buffer and the holder keeps its values (util/shared_mat.h).

 private:
  // What one frame in flight holds: Ahead fills one slot while Finish works on the other.
  struct Slot {
    Slot(const SegmentationOptions& segmentation, BipPool* pool,
         std::shared_ptr<DisparityEstimators> estimators, const DisparityOptions& disparity,
         std::vector<FeatureResult> features);
    StereoFrame frame;  // headers: the caller's images
    LazyFrameContext context;
    std::vector<FeatureResult> features;  // FeatureSet::NewResults()
    StageTimes timings;         // those of Ahead
  };

  // Slot `index`, given `frame`, its context reset.
  Slot& Begin(int index, const StereoFrame& frame);
  // Ahead's features (`phase`) with their wall time added to the slot's `features` time.
  void ComputeFeatures(Slot* slot, FeaturePhase phase, ThreadPool* pool);
  // The slot's feature maps normalised, weighted and combined by saliency_ (SPEC 2.3). Only
  // the frame that Finish works on needs them, so unlike the features' maps there is one
  // saliency stage, not one a slot (at 640x480, 6 MB less).
  void Saliency(Slot* slot);
  // Tracking (the existing targets) in the slot's frame.
  void Track(const Slot& slot);
  // Inhibition and selection in the slot's frame, and the record of its targets.
  void Select(const Slot& slot, FrameRecord* record);
  // What the attention stage takes of the stereo pair for the targets' disparities.
  StereoInput StereoOf(const Slot& slot) const;
  // The attention stage's targets as the frame's records (SPEC 3.3).
  void RecordTargets(FrameRecord* record) const;
  const Slot& current() const { return *slots_[current_]; }

  const AttendOptions options_;
  ExecutionContext* const execution_;
  const int threads_;  // the execution context's
  FeatureSet features_;
  SaliencyStage saliency_;
  bool grey_ = false;                 // of the current frame
  std::vector<const cv::Mat*> maps_;  // the features' maps, for saliency_
  // Two slots once Ahead is used (the second is made then), else one.
  std::unique_ptr<Slot> slots_[2];
  // Frames take the two slots in turn. Finish (and Process) set current_, the slot of the
  // accessors' frame; Ahead alone reads and sets ahead_slot_, the slot of its next frame.
  int current_ = 0;
  int ahead_slot_ = 1;
  // The frames given to Ahead whose Finish has not ended: at most two (Ahead of frame t + 1
  // beside the Finish of frame t).
  std::atomic<int> pending_{0};
  bool has_late_features_ = false;  // some feature reads where attention looked
  AttentionStage attention_;
  TrackedTargets tracked_;  // what attention_ tracked in this frame
  std::vector<Detection> detections_;  // the top-down channels' detections in this frame
  AttentionFrame attended_;
  bool has_disparity_ = false;  // the disparity feature is enabled
  DisparityOptions disparity_options_;  // its options: the frame contexts' disparity
  // The slots' contexts share the disparity's estimators (one cost volume, not two).
  std::shared_ptr<DisparityEstimators> estimators_ = std::make_shared<DisparityEstimators>();
  std::shared_ptr<const StereoCalibration> calibration_;
  double scale_x_ = 1.0, scale_y_ = 1.0;
};

}  // namespace attend
