// The bip kind of TargetTracker: MultiTracker (tracker/tracker.h) as it is.
#include <memory>
#include <string>
#include <vector>

#include "tracker/correlation_tracker.h"
#include "tracker/tracker_kinds.h"

namespace attend {

namespace {

class BipTargetTracker final : public TargetTracker {
 public:
  BipTargetTracker(const TrackerOptions& options, BipPool* pool) : tracker_(options, pool) {}

  int StartFromBox(const cv::Mat& frame, const cv::Rect& box, TrackSimilarity similarity,
                   const cv::Mat& skin) override {
    return tracker_.StartFromBox(frame, box, similarity, skin);
  }
  int StartFromMask(const cv::Mat& frame, const cv::Mat& mask, TrackSimilarity similarity,
                    const cv::Mat& skin) override {
    return tracker_.StartFromMask(frame, mask, similarity, skin);
  }
  int StartFromRegion(const cv::Mat& frame, const cv::Mat& labels, int region,
                      TrackSimilarity similarity, const cv::Mat& skin) override {
    return tracker_.StartFromRegion(frame, labels, region, similarity, skin);
  }
  void Track(const cv::Mat& frame, std::vector<TrackResult>* results, const cv::Mat& skin,
             const cv::Mat& cylinder) override {
    tracker_.Track(frame, results, skin, cylinder);
  }
  cv::Mat Mask(int id) const override { return tracker_.Mask(id); }
  void Remove(int id) override { tracker_.Remove(id); }
  std::vector<int> ids() const override { return tracker_.ids(); }
  TrackerKind kind() const override { return TrackerKind::kBip; }
  double milliseconds() const override { return tracker_.milliseconds(); }
  double segmentation_milliseconds() const override { return tracker_.segmentation_milliseconds(); }

 private:
  MultiTracker tracker_;
};

bool UsesBipKey(std::string_view key) {
  return HasKey(TrackerOptions::Fields(), key) || HasKey(CorrelationOptions::Fields(), key);
}

std::string CheckBip(const TargetTrackerOptions& options) {
  const std::string error = options.bip.Check();
  if (!error.empty() || options.bip.mode != TrackerMode::kCorrelation) return error;
  return options.correlation.Check();
}

// Which BIP tracker: the mode and, for the template modes, whether the occlusion rules (which
// the correlation mode does not read) were on.
std::vector<TrackerSetting> BipSettings(const TargetTrackerOptions& options) {
  if (options.bip.mode == TrackerMode::kCorrelation) return {{"mode", std::string("correlation")}};
  return {{"mode", std::string(TrackerModeName(options.bip.mode))},
          {"occlusion", options.bip.occlusion}};
}

// The correlation mode is a tracker of its own; the thesis and bounded modes are MultiTracker's.
std::unique_ptr<TargetTracker> CreateBip(const TargetTrackerOptions& options, BipPool* pool) {
  if (options.bip.mode == TrackerMode::kCorrelation) {
    return MakeCorrelationTracker(options.correlation, pool);
  }
  return std::make_unique<BipTargetTracker>(options.bip, pool);
}

}  // namespace

const TrackerKindInfo& BipKind() {
  static const TrackerKindInfo row = {
      .kind = TrackerKind::kBip,
      .name = "bip",
      .colour_similarity = "hsv",
      .skin_similarity = "skin",
      .uses_key = &UsesBipKey,
      .check = &CheckBip,
      // The bounded mode with its occlusion rules.
      .config_file = "track.yaml",
      .no_target =
          "no target: no region of the frame's over-segmentation lies mostly inside the "
          "box, or the target is too thin for a template",
      .settings = &BipSettings,
      .create = &CreateBip};
  return row;
}

}  // namespace attend
