#include "semiattentive/attention.h"

#include <algorithm>
#include <memory>
#include <optional>
#include <opencv2/imgproc.hpp>
#include <utility>

#include "features/skin.h"
#include "semiattentive/background.h"
#include "semiattentive/candidates.h"
#include "semiattentive/followed_targets.h"
#include "semiattentive/inhibition.h"
#include "semiattentive/motion_grouping.h"
#include "semiattentive/recognition.h"
#include "semiattentive/release.h"
#include "semiattentive/seeds.h"
#include "util/error.h"
#include "util/timer.h"

namespace attend {

namespace {

double MeanOver(const cv::Mat& map, const cv::Mat& mask) {
  return cv::countNonZero(mask) > 0 ? cv::mean(map, mask)[0] : 0.0;
}

// `options`, once they pass their check: the steps are built from them.
const AttentionOptions& Checked(const AttentionOptions& options) {
  const std::string error = options.Check();
  if (!error.empty()) throw ConfigError(error);
  return options;
}

}  // namespace

// The stage: its steps, each a unit of its own, and the state each keeps across frames. Its
// methods compose the steps, in the order Select calls them.
struct AttentionStage::Impl {
  Impl(const AttentionOptions& options, SkinModel skin_model, BipPool* pool);

  // What Select is given, for its steps.
  struct Frame {
    const cv::Mat& bgr;
    const cv::Mat& skin_distance;
    const TrackedTargets& tracked;
    const cv::Mat& saliency;
    const Segmentation& segmentation;
    const std::vector<Detection>& detections;
    cv::Rect image;
    const StereoInput& stereo;
  };

  void Track(const cv::Mat& bgr, const cv::Mat& skin_distance, TrackedTargets* tracked,
             const cv::Mat& cylinder);
  void Select(const Frame& in, AttentionFrame* frame);
  void SetFrameRate(double fps) {
    dwell_frames_ = options_.memory.dwell_s > 0.f
                        ? std::max(1, static_cast<int>(std::lround(options_.memory.dwell_s * fps)))
                        : 0;
  }
  // Why a found target kept so far is released by the rules of this stage's own: mostly on
  // background (select.background), attended for its dwell (attention.dwell_s).
  ReleaseReason WhyMovedOn(const cv::Mat& mask, const cv::Rect& box, FollowedTarget* followed);

  // The targets tracked this frame: their states, the release rules, recognition and
  // re-anchoring, their inhibition; ended targets are removed.
  void FollowTargets(const Frame& in, AttentionFrame* frame);
  // A found target (`result`, its `mask`, matched to detection `detection`): its state,
  // release, recognition and inhibition; appends its tracker id to `removed` when released.
  void FollowFound(const Frame& in, const TrackResult& result, const cv::Mat& mask, int detection,
                   FollowedTarget* followed, AttendedTarget* target, std::vector<int>* removed);
  // Recognition of a found target kept so far (Recogniser::Recognise), and its tracker's
  // restart when it re-anchors. Returns its mask.
  cv::Mat Recognise(const Frame& in, const TrackResult& result, const cv::Mat& mask, int detection,
                    FollowedTarget* followed, AttendedTarget* target);
  // A kept target (mask `own`): its inhibition, and what its object file would remember.
  void Keep(const Frame& in, const cv::Mat& own, const AttendedTarget& target,
            FollowedTarget* followed);
  // Starts new targets on the best candidates of the inhibited saliency, which inhibits
  // `inhibited_pixels`; `looked` gets the candidates' boxes.
  void StartTargets(const Frame& in, int inhibited_pixels, AttentionFrame* frame,
                    std::vector<cv::Rect>* looked);
  // Whether a seed on colour region `region` starts a skin target.
  bool IsSkin(const Frame& in, int region) const;
  // select.every_detection: starts targets on the free detections, the most salient first,
  // up to `limit` targets started this frame in all (`started` so far); `inhibited_area`
  // grows with each.
  void StartOnDetections(const Frame& in, const SeedFrame& seeds, int limit, double max_inhibited,
                         int* started, double* inhibited_area, CandidateRegions* under,
                         AttentionFrame* frame);
  // Starts a target on `seed` (a skin target when `skin`); false when its tracker does not
  // start.
  bool Start(const Frame& in, const Seed& seed, bool skin, AttentionFrame* frame);
  // Labels from the top-down channels: once given, a target keeps its label.
  void LabelTargets(const Frame& in, AttentionFrame* frame);
  // Where attention looked: the targets followed, the objects remembered, the candidates.
  void Look(const Frame& in, const AttentionFrame& frame, const std::vector<cv::Rect>& looked);
  // Leaves an object file for a target that ends.
  void Forget(const FollowedTarget& followed);
  // Depth in the loop: the pixels of the frame that a target at disparity `d` neither
  // inhibits (in front of it) nor covers (apart from it); empty when off or unknown.
  struct DepthMasks {
    cv::Mat in_front, apart;
  };
  DepthMasks DepthMasksOf(const Frame& in, const DisparityEstimate& d) const;
  // A seen target's disparity this frame (its mask `own`; `raw` its raw estimate when
  // measured already) and its centroid.
  void Depth(const Frame& in, const cv::Mat& own, AttendedTarget* target,
             DisparityEstimate raw = {}, bool measured = false);

  // What targets look like, with an embedding (attention.appearance): the target's box in
  // `bgr`, over its mask `own` (may be empty: the box); `embed` takes the embedding.
  ObjectAppearance AppearanceOf(const cv::Mat& bgr, const cv::Mat& own, const cv::Rect& box,
                                bool embed);

  AttentionOptions options_;
  SkinModel skin_model_;
  std::unique_ptr<Reidentifier> reidentifier_;  // attention.appearance set only
  std::unique_ptr<TargetTracker> tracker_;
  FollowedTargets targets_;
  ObjectFiles files_;
  Inhibition inhibition_;
  ReleaseRules release_;
  HeldPixels held_;  // drop.max_shared < 1 only
  Recogniser recogniser_;
  CandidateFinder candidates_;
  SeedMaker seeds_;
  std::unique_ptr<MotionGrouping> grouping_;  // select.group_min_speed > 0 only
  TargetDepths depths_;
  SceneAnalysis scene_;      // select.background and depth grouping
  int dwell_frames_ = 0;     // attention.dwell_s at the sequence's frame rate; 0: off
  // Per detection of the frame: a target is on it (recognised, or started on it).
  std::vector<uint8_t> detection_used_;
  std::vector<cv::Rect> look_regions_;
  // Where attention is: the centre of the last target started (select.proximity).
  std::optional<cv::Point2d> focus_;
};

AttentionStage::Impl::Impl(const AttentionOptions& options, SkinModel skin_model, BipPool* pool)
    : options_(Checked(options)),
      skin_model_(std::move(skin_model)),
      reidentifier_(options_.appearance.model.empty()
                        ? nullptr
                        : Reidentifier::Load(options_.appearance, "attention.appearance")),
      tracker_(TargetTracker::Create(options_.tracker, pool)),
      files_(options_.memory),
      inhibition_(options_.inhibition),
      release_(options_.select, options_.drop),
      recogniser_(options_.select, options_.drop, options_.label_overlap, reidentifier_.get()),
      candidates_(options_.select, pool),
      seeds_(options_.select),
      depths_(options_.depth),
      scene_(options_.select) {
  SetFrameRate(kDefaultFrameRate);
  if (options_.select.group_min_speed > 0.f) {
    grouping_ = std::make_unique<MotionGrouping>(options_.select.group_min_speed,
                                                 options_.select.group_flow_tolerance);
  }
}

void AttentionStage::Impl::Track(const cv::Mat& bgr, const cv::Mat& skin_distance,
                                 TrackedTargets* tracked, const cv::Mat& cylinder) {
  const Stopwatch stopwatch;
  tracked->skin = skin_distance < skin_model_.threshold;
  tracked->results.clear();
  tracker_->Track(bgr, &tracked->results, tracked->skin, cylinder);
  tracked->milliseconds = stopwatch.ElapsedMs();
}

void AttentionStage::Impl::Select(const Frame& in, AttentionFrame* frame) {
  frame->targets.clear();
  frame->new_ids.clear();
  frame->track_ms = in.tracked.milliseconds;
  files_.Age();
  if (grouping_ != nullptr) grouping_->NextFrame(in.bgr);
  Stopwatch stage;
  if (scene_.enabled()) {
    scene_.Analyse(in.segmentation, in.stereo.disparity, in.stereo.measured, in.stereo.ground);
  }
  FollowTargets(in, frame);
  const int inhibited_pixels = inhibition_.Apply(in.saliency, files_);
  frame->inhibited_fraction =
      static_cast<double>(inhibited_pixels) / inhibition_.inhibition().total();
  frame->inhibit_ms = stage.ElapsedMs();

  stage.Restart();
  std::vector<cv::Rect> looked;  // the boxes of the candidates weighed, best first
  StartTargets(in, inhibited_pixels, frame, &looked);
  LabelTargets(in, frame);
  std::sort(frame->targets.begin(), frame->targets.end(),
            [](const AttendedTarget& a, const AttendedTarget& b) { return a.id < b.id; });
  frame->select_ms = stage.ElapsedMs();
  Look(in, *frame, looked);
}

void AttentionStage::Impl::FollowTargets(const Frame& in, AttentionFrame* frame) {
  inhibition_.Reset(in.bgr.size());
  detection_used_.assign(in.detections.size(), 0);
  if (release_.duplicates()) held_.Reset(in.bgr.size());
  const std::vector<int> detection_of =
      recogniser_.MatchDetections(in.tracked.results, targets_, in.detections, in.image);
  std::vector<int> removed;  // tracker ids
  for (size_t r = 0; r < in.tracked.results.size(); ++r) {
    const TrackResult& result = in.tracked.results[r];
    FollowedTarget* followed = targets_.OfTracker(result.id);
    if (followed == nullptr) continue;
    AttendedTarget target;
    target.id = followed->id;
    target.box = result.box & in.image;
    target.skin = followed->skin;
    const cv::Mat mask = result.state == TrackState::kFound ? tracker_->Mask(result.id) : cv::Mat();
    if (result.state == TrackState::kFound && !mask.empty()) {
      FollowFound(in, result, mask, detection_of[r], followed, &target, &removed);
    } else if (result.state == TrackState::kOccluded) {
      target.state = TargetState::kOccluded;
      ++followed->unseen;
      ++followed->since_kept;
      target.saliency = target.box.empty() ? 0.0 : cv::mean(in.saliency(target.box))[0];
      const DepthMasks masks = DepthMasksOf(in, depths_.Last(target.id));
      inhibition_.AddOccluded(target.box, result.roi, in.image, masks.in_front, masks.apart);
    } else {
      target.state = TargetState::kLost;
      ++followed->unseen;
      ++followed->since_kept;
      removed.push_back(result.id);
      Forget(*followed);
      depths_.Forget(followed->id);
    }
    frame->targets.push_back(target);
  }
  for (const int id : removed) tracker_->Remove(id);
  targets_.RemoveTrackers(removed);
}

void AttentionStage::Impl::FollowFound(const Frame& in, const TrackResult& result,
                                       const cv::Mat& mask, int detection, FollowedTarget* followed,
                                       AttendedTarget* target, std::vector<int>* removed) {
  target->state = TargetState::kTracked;
  target->area = result.area;
  target->saliency = MeanOver(in.saliency, mask);
  followed->low_frames = release_.LowFrames(target->saliency, followed->low_frames);
  const double shared =
      release_.duplicates() && result.area > 0 ? held_.Shared(mask, result.area) : 0.0;
  target->reason =
      release_.WhyReleased(target->box, target->area, followed->low_frames, shared, in.image);
  if (target->reason == ReleaseReason::kNone) target->reason = WhyMovedOn(mask, target->box, followed);
  // Depth in the loop: a target whose disparity jumps has slid onto another object.
  const bool depth = depths_.enabled() && !in.stereo.empty();
  const DisparityEstimate raw =
      depth ? depths_.Measure(in.bgr, in.stereo, mask, target->box) : DisparityEstimate{};
  if (depth && options_.depth.jump_px > 0.f &&
      depths_.JumpOf(target->id, in.bgr, in.stereo, mask, target->box, raw) >
          options_.depth.jump_px &&
      target->reason == ReleaseReason::kNone) {
    target->reason = ReleaseReason::kDepthJump;
  }
  const cv::Mat own =
      target->reason == ReleaseReason::kNone && !in.detections.empty() && !followed->skin
          ? Recognise(in, result, mask, detection, followed, target)
          : mask;
  // Released targets inhibit nothing, from the frame they are released in.
  if (target->reason != ReleaseReason::kNone) {
    target->state = TargetState::kReleased;
    removed->push_back(followed->tracker_id);
    // A duplicate's object is another target's; any other release ends the object's
    // tracking, not the object (its file keeps the last box it was kept with).
    if (target->reason != ReleaseReason::kDuplicate) Forget(*followed);
    depths_.Forget(target->id);
    return;
  }
  // A target restarted on its detection is measured again on its new mask.
  if (depth) Depth(in, own, target, raw, own.data == mask.data);
  Keep(in, own, *target, followed);
}

ReleaseReason AttentionStage::Impl::WhyMovedOn(const cv::Mat& mask, const cv::Rect& box,
                                             FollowedTarget* followed) {
  ++followed->found_frames;
  // A target that has slid onto the road or the sky (or was started there by the thesis's
  // rules of an earlier frame) is no object.
  if (scene_.enabled() && scene_.OnBackground(mask, box, &followed->background_frames)) {
    return ReleaseReason::kBackground;
  }
  if (dwell_frames_ > 0 && followed->found_frames >= dwell_frames_) return ReleaseReason::kDwell;
  return ReleaseReason::kNone;
}

cv::Mat AttentionStage::Impl::Recognise(const Frame& in, const TrackResult& result,
                                        const cv::Mat& mask, int detection,
                                        FollowedTarget* followed, AttendedTarget* target) {
  Seed seed;
  const Recognition recognition = recogniser_.Recognise(
      in.bgr, in.segmentation, in.detections, target->box, detection, &seeds_, followed, &seed);
  if (recognition.unrecognised) target->reason = ReleaseReason::kUnrecognised;
  if (recognition.detection >= 0) detection_used_[recognition.detection] = 1;
  // Its box is its detection's, whatever its tracker says (select.detection_box).
  const bool detection_box = options_.select.detection_box && recognition.detection >= 0;
  const cv::Rect detected =
      detection_box ? in.detections[recognition.detection].box & in.image : cv::Rect();
  if (detection_box) target->box = detected;
  if (!recognition.reanchor) return mask;
  const int restarted =
      tracker_->StartFromMask(in.bgr, seed.mask, TrackSimilarity::kColour, in.tracked.skin);
  if (restarted < 0) return mask;
  tracker_->Remove(result.id);
  followed->tracker_id = restarted;
  cv::Mat own = tracker_->Mask(restarted);
  target->box = detection_box ? detected : cv::boundingRect(own) & in.image;
  target->area = cv::countNonZero(own);
  return own;
}

void AttentionStage::Impl::Keep(const Frame& in, const cv::Mat& own, const AttendedTarget& target,
                                FollowedTarget* followed) {
  const DepthMasks masks = DepthMasksOf(in, {target.disparity, target.disparity_sd});
  inhibition_.AddTarget(own, target.box, in.image, masks.in_front, masks.apart);
  if (release_.duplicates()) held_.Hold(own);
  // Its file remembers it as it was last seen on its object: with top-down channels, a
  // labelled target only in the frames a detection is on it (its tracker may drift in the
  // others). Its appearance serves the re-anchoring's gate as well as the object files.
  ++followed->since_kept;
  const bool appearances = files_.enabled() || options_.select.reanchor_min_similarity > 0.f;
  const bool recognised =
      in.detections.empty() || followed->label.empty() || followed->unrecognised == 0;
  if (appearances && recognised) {
    // The embedding every appearance.every frames kept (at once when it has none).
    const bool embed = reidentifier_ != nullptr &&
                       (followed->appearance.embedding.empty() ||
                        ++followed->since_embedding >= options_.appearance.every);
    if (embed) followed->since_embedding = 0;
    followed->Kept(target.box, AppearanceOf(in.bgr, own, target.box, embed));
  }
  followed->unseen = 0;
}

void AttentionStage::Impl::StartTargets(const Frame& in, int inhibited_pixels,
                                        AttentionFrame* frame, std::vector<cv::Rect>* looked) {
  const int free_slots = options_.select.max_targets - targets_.size();
  if (free_slots <= 0) return;
  // Background is no candidate: its saliency is left out of the selection (not out of the
  // inhibited map that is recorded), and its regions count as taken for the seeds.
  const cv::Mat& selectable =
      scene_.enabled() ? scene_.WithoutBackground(inhibition_.inhibited()) : inhibition_.inhibited();
  Candidates candidates = candidates_.Find(selectable);
  RankCandidates(options_.select, focus_ ? &*focus_ : nullptr, in.detections, in.bgr.size(),
                 &candidates);
  for (size_t k = 0; k < candidates.ranked.size() && k < kLookCandidates; ++k) {
    looked->push_back(candidates.Box(candidates.ranked[k].second));
  }
  const bool every_detection =
      options_.select.every_detection && options_.select.seed == SeedKind::kDetection;
  if (candidates.ranked.empty() && !every_detection) return;
  CandidateRegions under = RegionsUnder(candidates, in.segmentation, inhibition_.covered());
  if (scene_.enabled()) scene_.MarkTaken(&under.taken);
  // New targets are started only while the inhibition stays within
  // select.max_inhibited_fraction of the image: attention that covers everything attends
  // nothing (each new region counts with its own area).
  double inhibited_area = inhibited_pixels;
  const double max_inhibited = options_.select.max_inhibited_fraction * in.bgr.total();
  // The boxes of the targets followed now: a detection they already cover is attended.
  std::vector<cv::Rect> followed;
  if (options_.select.seed == SeedKind::kDetection) {
    for (const AttendedTarget& t : frame->targets) {
      if (t.state == TargetState::kTracked || t.state == TargetState::kOccluded) {
        followed.push_back(t.box);
      }
    }
  }
  const double max_area = options_.select.max_area_fraction * in.bgr.total();
  const SeedFrame seed_frame{in.segmentation, selectable, candidates, under,
                             in.detections,   detection_used_, followed,   max_area,
                             scene_.enabled() ? &scene_ : nullptr};
  int started = 0;
  for (size_t k = 0; k < candidates.ranked.size(); ++k) {
    if (started >= std::min(options_.select.max_new, free_slots)) break;
    Seed seed;
    if (!seeds_.Make(seed_frame, k, grouping_.get(), &seed)) continue;
    if (inhibited_area + seed.area > max_inhibited) continue;
    // A skin target is its skin region alone, whatever the seed.
    const bool skin = IsSkin(in, seed.best);
    if (skin) seed.members.resize(1), seed.area = in.segmentation.regions[seed.best].area;
    inhibited_area += seed.area;
    for (const int region : seed.members) under.taken[region] = 1;
    if (seed.detection >= 0 && !skin) detection_used_[seed.detection] = 1;
    if (Start(in, seed, skin, frame)) ++started;
  }
  if (every_detection) {
    StartOnDetections(in, seed_frame, std::min(options_.select.max_new, free_slots),
                      max_inhibited, &started, &inhibited_area, &under, frame);
  }
}

void AttentionStage::Impl::StartOnDetections(const Frame& in, const SeedFrame& seeds, int limit,
                                             double max_inhibited, int* started,
                                             double* inhibited_area, CandidateRegions* under,
                                             AttentionFrame* frame) {
  // The free detections, the most salient first.
  std::vector<std::pair<double, int>> order;
  for (size_t d = 0; d < in.detections.size(); ++d) {
    if (detection_used_[d]) continue;
    const cv::Rect box = in.detections[d].box & in.image;
    if (box.empty()) continue;
    order.emplace_back(cv::mean(inhibition_.inhibited()(box))[0], static_cast<int>(d));
  }
  std::stable_sort(order.begin(), order.end(),
                   [](const auto& a, const auto& b) { return a.first > b.first; });
  for (const auto& [saliency, d] : order) {
    (void)saliency;
    if (*started >= limit) break;
    Seed seed;
    if (!seeds_.FromDetection(seeds, d, &seed)) continue;
    if (*inhibited_area + seed.area > max_inhibited) continue;
    *inhibited_area += seed.area;
    for (const int region : seed.members) {
      if (region < static_cast<int>(under->taken.size())) under->taken[region] = 1;
    }
    detection_used_[d] = 1;
    if (Start(in, seed, false, frame)) ++*started;
  }
}

bool AttentionStage::Impl::IsSkin(const Frame& in, int region) const {
  const cv::Mat region_mask = in.segmentation.labels == region;
  const double region_area = in.segmentation.regions[region].area;
  const double skin_share =
      static_cast<double>(cv::countNonZero(in.tracked.skin & region_mask)) / region_area;
  // Skin targets: confident, skin-shaped skin of a person's size, unless skin_check is off.
  if (skin_share < options_.skin_fraction || !options_.skin_check) {
    return skin_share >= options_.skin_fraction;
  }
  return JudgeSkinRegion(region_mask, in.skin_distance, skin_model_.threshold,
                         options_.skin_region).skin &&
         !(scene_.WidthM(in.segmentation, region) > SceneAnalysis::kMaxSkinWidthM);
}

bool AttentionStage::Impl::Start(const Frame& in, const Seed& seed, bool skin,
                                 AttentionFrame* frame) {
  int tracker_id = -1;
  if (seed.detection >= 0 && !skin) {
    tracker_id =
        tracker_->StartFromMask(in.bgr, seed.mask, TrackSimilarity::kColour, in.tracked.skin);
  } else if (seed.members.size() == 1) {
    tracker_id = tracker_->StartFromRegion(in.bgr, in.segmentation.labels, seed.best,
                                           skin ? TrackSimilarity::kSkin : TrackSimilarity::kColour,
                                           in.tracked.skin);
  } else {
    tracker_id = tracker_->StartFromMask(in.bgr, seeds_.MaskOf(in.segmentation, seed.members),
                                         TrackSimilarity::kColour, in.tracked.skin);
  }
  if (tracker_id < 0) return false;
  const cv::Mat own = tracker_->Mask(tracker_id);
  AttendedTarget target;
  target.box = cv::boundingRect(own);
  target.area = cv::countNonZero(own);
  target.saliency = MeanOver(in.saliency, own);
  target.state = TargetState::kNew;
  target.skin = skin;
  focus_ = cv::Point2d(target.box.x + target.box.width / 2.0, target.box.y + target.box.height / 2.0);
  FollowedTarget followed;
  followed.tracker_id = tracker_id;
  followed.skin = skin;
  if (files_.enabled()) {
    // A remembered object attended again resumes its id, its label and its motion.
    followed.last_box = target.box;
    followed.appearance = AppearanceOf(in.bgr, own, target.box, !files_.files().empty());
    const int file = files_.Match(target.box, followed.appearance, skin);
    if (file >= 0) {
      ObjectFile resumed = files_.Take(file);
      target.state = TargetState::kResumed;
      // Its file counts the frames since it was last seen, this one included; a file left in
      // this very frame (a target released, its object started again at once) has 0.
      target.absent_frames = std::max(0, resumed.absent - 1);
      followed.Resume(std::move(resumed));
    }
  }
  target.id = targets_.Add(std::move(followed));
  depths_.Forget(target.id);  // a resumed object's disparity starts again
  if (depths_.enabled() && !in.stereo.empty()) {
    Depth(in, own, &target);
    // The jump test's series starts with the target (its first frame cannot jump).
    if (options_.depth.jump_px > 0.f) {
      const bool by_template = options_.depth.method == TargetDisparityMethod::kTemplate;
      depths_.JumpOf(target.id, in.bgr, in.stereo, own, target.box,
                     by_template ? depths_.Measure(in.bgr, in.stereo, own, target.box)
                                 : DisparityEstimate{});
    }
  }
  if (target.state == TargetState::kNew) frame->new_ids.push_back(target.id);
  frame->targets.push_back(target);
  return true;
}

ObjectAppearance AttentionStage::Impl::AppearanceOf(const cv::Mat& bgr, const cv::Mat& own,
                                                   const cv::Rect& box, bool embed) {
  ObjectAppearance appearance = ObjectAppearance::Of(bgr, own, box);
  if (embed && reidentifier_ != nullptr && !appearance.empty()) {
    appearance.embedding = reidentifier_->Embed(bgr, box);
  }
  return appearance;
}

void AttentionStage::Impl::LabelTargets(const Frame& in, AttentionFrame* frame) {
  if (!in.detections.empty()) {
    for (AttendedTarget& target : frame->targets) {
      if (!Visible(target.state)) continue;
      FollowedTarget* followed = targets_.WithId(target.id);
      if (followed == nullptr || !followed->label.empty()) continue;
      followed->label = recogniser_.LabelOf(target.box, in.detections);
    }
  }
  for (AttendedTarget& target : frame->targets) {
    const FollowedTarget* followed = targets_.WithId(target.id);
    if (followed != nullptr) target.label = followed->label;
  }
}

void AttentionStage::Impl::Look(const Frame& in, const AttentionFrame& frame,
                                const std::vector<cv::Rect>& looked) {
  look_regions_.clear();
  for (const AttendedTarget& target : frame.targets) {
    if ((Visible(target.state) || target.state == TargetState::kOccluded) && !target.box.empty()) {
      look_regions_.push_back(target.box);
    }
  }
  for (const cv::Rect& box : files_.PredictedBoxes(in.image)) look_regions_.push_back(box);
  look_regions_.insert(look_regions_.end(), looked.begin(), looked.end());
}

void AttentionStage::Impl::Depth(const Frame& in, const cv::Mat& own, AttendedTarget* target,
                                 DisparityEstimate raw, bool measured) {
  if (!measured) raw = depths_.Measure(in.bgr, in.stereo, own, target->box);
  const DisparityEstimate filtered = depths_.Update(target->id, raw);
  target->disparity = filtered.disparity;
  target->disparity_sd = filtered.sd;
  target->depth_unmeasured = raw.unmeasured;
  const cv::Moments moments = cv::moments(own(target->box & in.image), true);
  if (moments.m00 > 0) {
    target->centroid = cv::Point2f(static_cast<float>(moments.m10 / moments.m00 + target->box.x),
                                   static_cast<float>(moments.m01 / moments.m00 + target->box.y));
  }
}

AttentionStage::Impl::DepthMasks AttentionStage::Impl::DepthMasksOf(
    const Frame& in, const DisparityEstimate& d) const {
  DepthMasks masks;
  if (in.stereo.disparity.empty() || !d.valid()) return masks;
  const DepthOptions& depth = options_.depth;
  if (depth.inhibit_band_px > 0.f) {
    masks.in_front = in.stereo.disparity > d.disparity + depth.inhibit_band_px;
  }
  if (depth.separate_px > 0.f) {
    cv::Mat distance;
    cv::absdiff(in.stereo.disparity, cv::Scalar(d.disparity), distance);
    masks.apart = distance > depth.separate_px;
  }
  return masks;
}

void AttentionStage::Impl::Forget(const FollowedTarget& followed) {
  if (!files_.enabled() || followed.last_box.empty()) return;
  files_.Remember(followed.File());
}

AttentionStage::AttentionStage(const AttentionOptions& options, SkinModel skin_model, BipPool* pool)
    : impl_(std::make_unique<Impl>(options, std::move(skin_model), pool)) {}

AttentionStage::~AttentionStage() = default;

const SkinModel& AttentionStage::skin_model() const { return impl_->skin_model_; }

void AttentionStage::Track(const cv::Mat& bgr, const cv::Mat& skin_distance,
                           TrackedTargets* tracked, const cv::Mat& cylinder) {
  impl_->Track(bgr, skin_distance, tracked, cylinder);
}

void AttentionStage::Select(const cv::Mat& bgr, const cv::Mat& skin_distance,
                            const TrackedTargets& tracked, const cv::Mat& saliency,
                            const Segmentation& segmentation, AttentionFrame* frame,
                            const std::vector<Detection>& detections, const StereoInput& stereo) {
  // Maps of the last frame that someone still holds are let go (util/shared_mat.h).
  impl_->inhibition_.ReleaseShared();
  impl_->Select({bgr, skin_distance, tracked, saliency, segmentation, detections,
                 cv::Rect(0, 0, bgr.cols, bgr.rows), stereo},
                frame);
}

void AttentionStage::SetFrameRate(double fps) { impl_->SetFrameRate(fps); }
void AttentionStage::SetBaseline(double baseline_m) { impl_->scene_.set_baseline(baseline_m); }

const std::vector<cv::Rect>& AttentionStage::look_regions() const { return impl_->look_regions_; }
const ObjectFiles& AttentionStage::object_files() const { return impl_->files_; }
const cv::Mat& AttentionStage::background() const { return impl_->scene_.regions().mask; }
const cv::Mat& AttentionStage::inhibition() const { return impl_->inhibition_.inhibition(); }
const cv::Mat& AttentionStage::inhibited() const { return impl_->inhibition_.inhibited(); }
int AttentionStage::targets_attended() const { return impl_->targets_.attended(); }
const char* AttentionStage::tracker_name() const { return impl_->tracker_->name(); }

}  // namespace attend
