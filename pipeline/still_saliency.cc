#include "pipeline/still_saliency.h"

#include <algorithm>
#include <opencv2/imgproc.hpp>

#include "io/sequence.h"
#include "pipeline/frame_pipeline.h"
#include "io/frame_record.h"

namespace attend {

namespace {

// A map of the working size at the image's size (bilinear; maps are smooth or piecewise
// constant, and the metrics compare them at the stimulus's pixels).
cv::Mat ToImageSize(const cv::Mat& map, cv::Size size) {
  if (map.size() == size) return map.clone();
  cv::Mat out;
  cv::resize(map, out, size, 0, 0, cv::INTER_LINEAR);
  return out;
}

}  // namespace

StillSaliency::StillSaliency(const AttendOptions& options, const std::string& home,
                             std::vector<std::string>* dropped)
    : options_(options),
      home_(home),
      registry_(LoadFeatureRegistry(options_.plugins)),
      execution_(std::make_unique<ExecutionContext>(options.threads)) {
  FeatureSetup setup;
  setup.home = home_;
  const std::vector<std::string> left_out =
      LeaveOutStereoFeatures(registry_, setup, &options_.features);
  if (dropped != nullptr) dropped->insert(dropped->end(), left_out.begin(), left_out.end());
  // Every other problem of the configuration shows here, before any image is read.
  setup.stereo = false;
  FramePipeline check(options_, registry_, setup, execution_.get());
}

StillMaps StillSaliency::Compute(const cv::Mat& bgr, bool with_features, int scanpath_steps,
                                 ScanpathPoint point) const {
  CV_Assert(bgr.type() == CV_8UC3 && !bgr.empty());
  // A pipeline per image: nothing (motion background, targets, inhibition) carries over.
  FeatureSetup setup;
  setup.stereo = false;
  setup.home = home_;
  FramePipeline pipeline(options_, registry_, setup, execution_.get());

  StillMaps maps;
  maps.image_size = bgr.size();
  maps.working_size = WorkingSize(options_.sequence, bgr.size());
  StereoFrame frame;
  frame.index = 0;
  frame.left = ToWorkingSize(bgr, maps.working_size);
  // Each image is a sequence of its own (shown again for the scanpath below).
  pipeline.BeginSequence({"", maps.working_size, false, 0});
  FrameRecord record;
  pipeline.Process(frame, &record);
  maps.saliency = ToImageSize(pipeline.saliency(), maps.image_size);
  if (with_features) {
    for (size_t i = 0; i < pipeline.features().size(); ++i) {
      maps.feature_names.push_back(pipeline.features()[i].name);
      maps.features.push_back(ToImageSize(pipeline.normalised()[i], maps.image_size));
    }
  }
  // Attention on the still image: the same frame again, each showing selects new targets
  // where the inhibition leaves the saliency high.
  // Working size over input size, as SequenceInfo's scale_x and scale_y.
  const double sx = static_cast<double>(maps.working_size.width) / maps.image_size.width;
  const double sy = static_cast<double>(maps.working_size.height) / maps.image_size.height;
  // The map the stage selected on at each showing: the saliency at the first, then the
  // saliency as the previous showing left it inhibited (every target started before).
  cv::Mat selected_on = pipeline.saliency().clone();
  // A target too small for the stage to keep is released at once and so never inhibited: the
  // next showing starts it again on the same pixels. That is not a new step; two showings in a
  // row without one end the scanpath.
  int showings_without_step = 0;
  for (int shown = 0; static_cast<int>(maps.scanpath.size()) < scanpath_steps; ++shown) {
    if (shown > 0) {
      pipeline.inhibited().copyTo(selected_on);
      frame.index = shown;
      record = FrameRecord();
      pipeline.Process(frame, &record);
    }
    if (record.new_ids.empty()) break;
    const size_t steps_before = maps.scanpath.size();
    for (const int id : record.new_ids) {
      for (const TargetRecord& target : record.targets) {
        if (target.id != id) continue;
        const cv::Rect box = InputFromWorkingBox(target.bbox, sx, sy, maps.image_size);
        if (std::find(maps.scanpath_boxes.begin(), maps.scanpath_boxes.end(), box) !=
            maps.scanpath_boxes.end()) {
          continue;
        }
        maps.scanpath_boxes.push_back(box);
        const cv::Rect inside = target.bbox & cv::Rect(cv::Point(), maps.working_size);
        if (point == ScanpathPoint::kPeak && !inside.empty()) {
          cv::Point peak;
          cv::minMaxLoc(selected_on(inside), nullptr, nullptr, nullptr, &peak);
          // The working pixel's centre in input pixels.
          maps.scanpath.emplace_back((inside.x + peak.x + 0.5) / sx - 0.5,
                                     (inside.y + peak.y + 0.5) / sy - 0.5);
        } else {
          maps.scanpath.emplace_back(box.x + box.width / 2.0, box.y + box.height / 2.0);
        }
      }
    }
    showings_without_step = maps.scanpath.size() > steps_before ? 0 : showings_without_step + 1;
    if (showings_without_step >= 2) break;
  }
  pipeline.EndSequence();
  if (static_cast<int>(maps.scanpath.size()) > scanpath_steps) {
    maps.scanpath.resize(scanpath_steps);
    maps.scanpath_boxes.resize(scanpath_steps);
  }
  return maps;
}

}  // namespace attend
