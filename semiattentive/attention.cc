#include "semiattentive/attention.h"

#include <algorithm>
#include <map>
#include <opencv2/imgproc.hpp>

#include "features/skin.h"
#include "pyramid/similarity.h"
#include "util/error.h"
#include "util/timer.h"

namespace attend {

struct AttentionStage::Active {
  int id = 0;
  bool skin = false;
  int low_frames = 0;  // consecutive frames below drop.min_saliency
};

const std::vector<std::string>& SelectOptions::Seeds() {
  static const std::vector<std::string> seeds = {"region", "object"};
  return seeds;
}

const FieldRanges<SelectOptions>& SelectOptions::Ranges() {
  using O = SelectOptions;
  static const FieldRanges<SelectOptions> ranges = {
      {"min_saliency", &O::min_saliency, Range::Closed(0, 1)},
      {"min_area", &O::min_area, Range::Closed(1, 1e8)},
      {"max_new", &O::max_new, Range::Closed(1, 1000)},
      {"max_targets", &O::max_targets, Range::Closed(1, 1000)},
      {"max_area_fraction", &O::max_area_fraction, Range::Closed(0.001, 1)},
      {"max_inhibited_fraction", &O::max_inhibited_fraction, Range::Closed(0.001, 1)},
      {"saliency_t_max", &O::saliency_t_max, Range::Closed(0.001, 1000)},
      {"seed_share", &O::seed_share, Range::Closed(0.01, 1)},
      {"seed_level", &O::seed_level, Range::Closed(0.01, 1)}};
  return ranges;
}

const FieldRanges<DropOptions>& DropOptions::Ranges() {
  static const FieldRanges<DropOptions> ranges = {
      {"min_saliency", &DropOptions::min_saliency, Range::Closed(0, 1)},
      {"frames", &DropOptions::frames, Range::Closed(1, 1e6)},
      {"max_shared", &DropOptions::max_shared, Range::Closed(0, 1)}};
  return ranges;
}

const FieldRanges<InhibitionOptions>& InhibitionOptions::Ranges() {
  static const FieldRanges<InhibitionOptions> ranges = {
      {"margin", &InhibitionOptions::margin, Range::Closed(0, 1000)}};
  return ranges;
}

const FieldRanges<AttentionOptions>& AttentionOptions::Ranges() {
  static const FieldRanges<AttentionOptions> ranges = {
      {"skin_fraction", &AttentionOptions::skin_fraction, Range::Closed(0, 1)}};
  return ranges;
}

std::string AttentionOptions::Check() const {
  std::string error = CheckFieldRanges(select, SelectOptions::Ranges());
  if (!error.empty()) return "select." + error;
  if (std::find(SelectOptions::Seeds().begin(), SelectOptions::Seeds().end(), select.seed) ==
      SelectOptions::Seeds().end()) {
    return "select.seed must be region or object";
  }
  error = CheckFieldRanges(drop, DropOptions::Ranges());
  if (!error.empty()) return "drop." + error;
  error = CheckFieldRanges(inhibition, InhibitionOptions::Ranges());
  if (!error.empty()) return "inhibition." + error;
  error = CheckFieldRanges(*this, Ranges());
  if (!error.empty()) return error;
  error = skin_region.Check();
  if (!error.empty()) return "select.skin_region: " + error;
  error = tracker.Check();
  if (!error.empty()) return "tracker." + error;
  return "";
}

AttentionStage::AttentionStage(const AttentionOptions& options, SkinModel skin_model)
    : options_(options), skin_model_(std::move(skin_model)) {
  const std::string error = options_.Check();
  if (!error.empty()) throw ConfigError(error);
  tracker_ = TargetTracker::Create(options_.tracker);
}

AttentionStage::~AttentionStage() = default;

void AttentionStage::Track(const cv::Mat& bgr, const cv::Mat& skin_distance,
                           TrackedTargets* tracked, const cv::Mat& cylinder) {
  const Stopwatch stopwatch;
  tracked->skin = skin_distance < skin_model_.threshold;
  tracked->results.clear();
  tracker_->Track(bgr, &tracked->results, tracked->skin, cylinder);
  tracked->milliseconds = stopwatch.ElapsedMs();
}

namespace {

double MeanOver(const cv::Mat& map, const cv::Mat& mask) {
  return cv::countNonZero(mask) > 0 ? cv::mean(map, mask)[0] : 0.0;
}

}  // namespace

ReleaseReason AttentionStage::WhyReleased(const AttendedTarget& target, int low_frames,
                                          double shared, const cv::Rect& image) const {
  if (target.area > options_.select.max_area_fraction * image.area()) {
    return ReleaseReason::kTooLarge;
  }
  if (target.box.width >= kSpansImageFraction * image.width &&
      target.box.height >= kSpansImageFraction * image.height) {
    return ReleaseReason::kSpansImage;
  }
  if (target.box.area() < options_.select.min_area) return ReleaseReason::kTooSmall;
  if (low_frames >= options_.drop.frames) return ReleaseReason::kLowSaliency;
  if (shared > options_.drop.max_shared) return ReleaseReason::kDuplicate;
  return ReleaseReason::kNone;
}

void AttentionStage::Select(const cv::Mat& bgr, const cv::Mat& skin_distance,
                            const TrackedTargets& tracked, const cv::Mat& saliency,
                            const Segmentation& segmentation, AttentionFrame* frame) {
  frame->targets.clear();
  frame->new_ids.clear();
  frame->track_ms = tracked.milliseconds;
  const cv::Rect image(0, 0, bgr.cols, bgr.rows);

  // The states of the targets tracked this frame, their saliency and the drop rule.
  Stopwatch stage;
  inhibition_.create(bgr.size(), CV_32FC1);
  inhibition_.setTo(0.f);
  covered_.create(bgr.size(), CV_8UC1);
  covered_.setTo(0);
  const int margin = options_.inhibition.margin;
  const cv::Mat kernel =
      cv::getStructuringElement(cv::MORPH_RECT, cv::Size(2 * margin + 1, 2 * margin + 1));
  std::vector<int> removed;
  // The pixels of the targets found and kept so far this frame, in id order: a younger
  // target most of whose mask an older one already holds is a duplicate (drop.max_shared).
  const bool duplicates = options_.drop.max_shared < 1.f;
  if (duplicates) {
    held_.create(bgr.size(), CV_8UC1);
    held_.setTo(0);
  }
  for (const TrackResult& result : tracked.results) {
    auto active = std::find_if(active_.begin(), active_.end(),
                               [&](const Active& a) { return a.id == result.id; });
    if (active == active_.end()) continue;
    AttendedTarget target;
    target.id = result.id;
    target.box = result.box & image;
    target.skin = active->skin;
    const cv::Mat mask = result.state == TrackState::kFound ? tracker_->Mask(result.id) : cv::Mat();
    if (result.state == TrackState::kFound && !mask.empty()) {
      target.state = TargetState::kTracked;
      target.area = result.area;
      target.saliency = MeanOver(saliency, mask);
      active->low_frames =
          target.saliency < options_.drop.min_saliency ? active->low_frames + 1 : 0;
      const double shared = duplicates && result.area > 0
                                ? static_cast<double>(cv::countNonZero(held_ & mask)) / result.area
                                : 0.0;
      target.reason = WhyReleased(target, active->low_frames, shared, image);
      // Released targets inhibit nothing, from the frame they are released in.
      if (target.reason != ReleaseReason::kNone) {
        target.state = TargetState::kReleased;
        removed.push_back(result.id);
      } else {
        // Inhibit the mask, dilated, within its box plus the margin.
        const cv::Rect around =
            cv::Rect(target.box.x - margin, target.box.y - margin, target.box.width + 2 * margin,
                     target.box.height + 2 * margin) &
            image;
        cv::Mat grown;
        cv::dilate(mask(around), grown, kernel);
        inhibition_(around).setTo(1.f, grown);
        covered_.setTo(255, mask);
        if (duplicates) held_.setTo(255, mask);
      }
    } else if (result.state == TrackState::kOccluded) {
      target.state = TargetState::kOccluded;
      target.saliency = target.box.empty() ? 0.0 : cv::mean(saliency(target.box))[0];
      if (options_.inhibition.keep_occluded && !target.box.empty()) {
        const cv::Rect area = options_.inhibition.occluded_search && !result.roi.empty()
                                  ? (target.box | result.roi) & image
                                  : target.box;
        inhibition_(area).setTo(1.f);
        covered_(area).setTo(255);
      }
    } else {
      target.state = TargetState::kLost;
      removed.push_back(result.id);
    }
    frame->targets.push_back(target);
  }
  for (const int id : removed) {
    tracker_->Remove(id);
    active_.erase(std::remove_if(active_.begin(), active_.end(),
                                 [id](const Active& a) { return a.id == id; }),
                  active_.end());
  }
  cv::subtract(cv::Scalar(1.f), inhibition_, inhibited_);
  cv::multiply(saliency, inhibited_, inhibited_);
  const int inhibited_pixels = cv::countNonZero(inhibition_);
  frame->inhibited_fraction = static_cast<double>(inhibited_pixels) / inhibition_.total();
  frame->inhibit_ms = stage.ElapsedMs();

  // Candidates: regions of homogeneous inhibited saliency (a BIP over the saliency map).
  stage.Restart();
  const int free_slots = options_.select.max_targets - static_cast<int>(active_.size());
  if (free_slots > 0) {
    cv::Mat scaled, features;
    inhibited_.convertTo(scaled, CV_32F, 255.0);
    const cv::Mat zero = cv::Mat::zeros(scaled.size(), CV_32FC1);
    cv::merge(std::vector<cv::Mat>{scaled, zero, zero}, features);
    const Bip& bip =
        saliency_builder_.Build(features, HsvSimilarity(options_.select.saliency_t_max));
    cv::Mat labels;
    const int count = bip.LabelRoots(&labels);
    std::vector<double> sum(count, 0.0);
    std::vector<int> area(count, 0);
    std::vector<cv::Point> peak(count);  // each region's most salient pixel
    std::vector<float> peak_value(count, -1.f);
    for (int y = 0; y < labels.rows; ++y) {
      const int* label = labels.ptr<int>(y);
      const float* s = inhibited_.ptr<float>(y);
      for (int x = 0; x < labels.cols; ++x) {
        if (label[x] < 0) continue;
        sum[label[x]] += s[x];
        ++area[label[x]];
        if (s[x] > peak_value[label[x]]) peak_value[label[x]] = s[x], peak[label[x]] = {x, y};
      }
    }
    std::vector<std::pair<double, int>> ranked;  // (mean * area, region)
    for (int r = 0; r < count; ++r) {
      const double mean = area[r] > 0 ? sum[r] / area[r] : 0.0;
      if (mean >= options_.select.min_saliency && area[r] >= options_.select.min_area) {
        ranked.push_back({mean * area[r], r});
      }
    }
    std::stable_sort(ranked.begin(), ranked.end(),
                     [](const auto& a, const auto& b) { return a.first > b.first; });

    if (!ranked.empty()) {
      // The colour regions under each candidate, and those an active target covers.
      std::vector<int> candidate_of(count, -1);
      for (size_t k = 0; k < ranked.size(); ++k)
        candidate_of[ranked[k].second] = static_cast<int>(k);
      std::vector<std::map<int, int>> overlaps(ranked.size());
      const cv::Mat& colour = segmentation.labels;
      std::vector<uint8_t> taken(segmentation.regions.size(), 0);
      for (int y = 0; y < labels.rows; ++y) {
        const int* label = labels.ptr<int>(y);
        const int* region = colour.ptr<int>(y);
        const uchar* covered = covered_.ptr<uchar>(y);
        for (int x = 0; x < labels.cols; ++x) {
          if (region[x] < 0) continue;
          if (covered[x]) taken[region[x]] = 1;
          if (label[x] >= 0 && candidate_of[label[x]] >= 0) {
            ++overlaps[candidate_of[label[x]]][region[x]];
          }
        }
      }
      const double max_area = options_.select.max_area_fraction * bgr.total();
      // New targets are started only while the inhibition stays within
      // select.max_inhibited_fraction of the image: attention that covers everything attends
      // nothing (each new region counts with its own area).
      double inhibited_area = inhibited_pixels;
      const double max_inhibited = options_.select.max_inhibited_fraction * bgr.total();
      const bool object_seed = options_.select.seed == "object";
      int started = 0;
      for (size_t k = 0; k < ranked.size(); ++k) {
        if (started >= std::min(options_.select.max_new, free_slots)) break;
        int best = -1, best_count = 0;
        for (const auto& [region, pixels] : overlaps[k]) {
          if (pixels > best_count) best = region, best_count = pixels;
        }
        if (best < 0 || taken[best] || segmentation.regions[best].area > max_area) continue;
        // The seed: the best region alone, or with the regions mostly inside the candidate.
        std::vector<int> members = {best};
        double seed_area = segmentation.regions[best].area;
        if (object_seed) {
          // The proto-object: the connected pixels around the candidate's most salient one
          // whose inhibited saliency is at least seed_level times the candidate's mean.
          const int r = ranked[k].second;
          const float level =
              static_cast<float>(options_.select.seed_level * sum[r] / std::max(1, area[r]));
          fill_mask_.create(inhibited_.rows + 2, inhibited_.cols + 2, CV_8UC1);
          fill_mask_.setTo(0);
          cv::Rect filled;
          const float from = std::min(level, peak_value[r]);
          cv::floodFill(inhibited_, fill_mask_, peak[r], cv::Scalar(), &filled,
                        cv::Scalar(peak_value[r] - from), cv::Scalar(1e6),
                        4 | cv::FLOODFILL_FIXED_RANGE | cv::FLOODFILL_MASK_ONLY | (255 << 8));
          std::map<int, int> inside;  // colour region -> its pixels in the proto-object
          for (int y = filled.y; y < filled.y + filled.height; ++y) {
            const int* region = colour.ptr<int>(y);
            const uchar* in = fill_mask_.ptr<uchar>(y + 1) + 1;
            for (int x = filled.x; x < filled.x + filled.width; ++x) {
              if (in[x] && region[x] >= 0) ++inside[region[x]];
            }
          }
          for (const auto& [region, pixels] : inside) {
            const int region_area = segmentation.regions[region].area;
            if (region == best || taken[region] || region_area > max_area ||
                pixels < options_.select.seed_share * region_area) {
              continue;
            }
            members.push_back(region);
            seed_area += region_area;
          }
          if (seed_area > max_area) members.resize(1), seed_area = segmentation.regions[best].area;
        }
        if (inhibited_area + seed_area > max_inhibited) continue;
        const cv::Mat region_mask = colour == best;
        const double skin_share =
            static_cast<double>(cv::countNonZero(tracked.skin & region_mask)) /
            segmentation.regions[best].area;
        // A mostly-skin region is a skin target only when it is confident, skin-shaped skin
        // (features/skin.h, JudgeSkinRegion), unless skin_check is off (the thesis's rule).
        // A skin target is its skin region alone, whatever the seed.
        const bool skin =
            skin_share >= options_.skin_fraction &&
            (!options_.skin_check || JudgeSkinRegion(region_mask, skin_distance,
                                                     skin_model_.threshold, options_.skin_region)
                                         .skin);
        if (skin) members.resize(1), seed_area = segmentation.regions[best].area;
        inhibited_area += seed_area;
        for (const int region : members) taken[region] = 1;
        int id = -1;
        if (members.size() == 1) {
          id = tracker_->StartFromRegion(bgr, colour, best,
                                         skin ? TrackSimilarity::kSkin : TrackSimilarity::kColour,
                                         tracked.skin);
        } else {
          member_.assign(segmentation.regions.size(), 0);
          for (const int region : members) member_[region] = 1;
          seed_mask_.create(colour.size(), CV_8UC1);
          for (int y = 0; y < colour.rows; ++y) {
            const int* region = colour.ptr<int>(y);
            uchar* out = seed_mask_.ptr<uchar>(y);
            for (int x = 0; x < colour.cols; ++x) {
              out[x] = region[x] >= 0 && member_[region[x]] ? 255 : 0;
            }
          }
          id = tracker_->StartFromMask(bgr, seed_mask_, TrackSimilarity::kColour, tracked.skin);
        }
        if (id < 0) continue;
        active_.push_back({id, skin, 0});
        ++attended_;
        ++started;
        AttendedTarget target;
        target.id = id;
        const cv::Mat own = tracker_->Mask(id);
        target.box = cv::boundingRect(own);
        target.area = cv::countNonZero(own);
        target.saliency = MeanOver(saliency, own);
        target.state = TargetState::kNew;
        target.skin = skin;
        frame->targets.push_back(target);
        frame->new_ids.push_back(id);
      }
    }
  }
  std::sort(frame->targets.begin(), frame->targets.end(),
            [](const AttendedTarget& a, const AttendedTarget& b) { return a.id < b.id; });
  frame->select_ms = stage.ElapsedMs();
}

}  // namespace attend
