#include "semiattentive/attention.h"

#include <algorithm>
#include <map>
#include <memory>
#include <opencv2/imgproc.hpp>
#include <utility>

#include "features/skin.h"
#include "pyramid/similarity.h"
#include "util/assignment.h"
#include "util/opencv_extra.h"
#include "util/box.h"
#include "util/enum_table.h"
#include "util/error.h"
#include "util/shared_mat.h"
#include "util/timer.h"

namespace attend {


namespace {

constexpr EnumTable<SeedKind, 3> kSeedKinds = {{{
    {SeedKind::kRegion, "region"},
    {SeedKind::kObject, "object"},
    {SeedKind::kDetection, "detection"},
}}};

}  // namespace

const char* SeedKindName(SeedKind seed) { return kSeedKinds.Name(seed); }

const OptionFields<SelectOptions>& SelectOptions::Fields() {
  using O = SelectOptions;
  static const OptionFields<SelectOptions> fields = {
      {"min_saliency", &O::min_saliency, Range::Closed(0, 1),
       "a candidate region's mean inhibited saliency at least this"},
      {"min_area", &O::min_area, Range::Closed(1, 1e8), "a candidate's area at least this, px"},
      {"max_new", &O::max_new, Range::Closed(1, 1000), "targets started in one frame"},
      {"max_targets", &O::max_targets, Range::Closed(1, 1000), "targets active at once"},
      {"max_area_fraction", &O::max_area_fraction, Range::Closed(0.001, 1),
       "a colour region larger than this share of the image is background"},
      {"max_inhibited_fraction", &O::max_inhibited_fraction, Range::Closed(0.001, 1),
       "no new target while the inhibition would cover more of the image; 1: no bound"},
      {"saliency_t_max", &O::saliency_t_max, Range::Closed(0.001, 1000),
       "T_max of the BIP that segments the saliency map (saliency x 255)"},
      {"seed", EnumField<&O::seed, kSeedKinds>(),
       "what a candidate starts as: its colour region, the object around it, or a detection"},
      {"seed_share", &O::seed_share, Range::Closed(0.01, 1),
       "object/detection: a colour region joins the seed when this share of it lies inside"},
      {"seed_level", &O::seed_level, Range::Closed(0.01, 1),
       "object: the salient region is where saliency is at least this times the mean"},
      {"detection_taken", &O::detection_taken, Range::Closed(0, 1),
       "detection: a detection an active target covers by this share belongs to it"},
      {"detected_only", &O::detected_only,
       "detection: a candidate under no detection starts nothing"},
      {"reanchor_min_iou", &O::reanchor_min_iou, Range::Closed(0, 1),
       "a found target restarts on a detection overlapping it at least this (IoU); 0: never"},
      {"reanchor_max_iou", &O::reanchor_max_iou, Range::Closed(0, 1),
       "... and below this IoU"},
      {"reanchor_min_similarity", &O::reanchor_min_similarity, Range::Closed(0, 1),
       "... and when the detection looks at least this like the target; 0: any look"},
      {"group_min_speed", &O::group_min_speed, Range::Closed(0, 1000),
       "object: motion grouping above this speed, px a frame; 0: off"},
      {"group_flow_tolerance", &O::group_flow_tolerance, Range::Closed(0, 10),
       "motion grouping: a region joins when its flow differs by at most this times the speed"}};
  return fields;
}

const OptionFields<DropOptions>& DropOptions::Fields() {
  using O = DropOptions;
  static const OptionFields<DropOptions> fields = {
      {"min_saliency", &O::min_saliency, Range::Closed(0, 1),
       "a target below this uninhibited saliency for `frames` frames is released"},
      {"frames", &O::frames, Range::Closed(1, 1e6), "frames of low saliency before release"},
      {"max_shared", &O::max_shared, Range::Closed(0, 1),
       "a target more of whose mask older targets hold is a duplicate; 1: never"},
      {"unrecognised_frames", &O::unrecognised_frames, Range::Closed(0, 1e6),
       "a labelled target no detection overlapped this many frames is released; 0: never"}};
  return fields;
}

const OptionFields<InhibitionOptions>& InhibitionOptions::Fields() {
  using O = InhibitionOptions;
  static const OptionFields<InhibitionOptions> fields = {
      {"margin", &O::margin, Range::Closed(0, 1000), "dilation around each tracked mask, px"},
      {"keep_occluded", &O::keep_occluded, "occluded targets inhibit their last box"},
      {"occluded_search", &O::occluded_search,
       "... and the area their tracker searched them in"}};
  return fields;
}

const OptionFields<AttentionOptions>& AttentionOptions::Fields() {
  using O = AttentionOptions;
  static const OptionFields<AttentionOptions> fields = {
      {"label_overlap", &O::label_overlap, Range::Closed(0, 1),
       "a target takes a detection's label when their boxes overlap by this share"},
      {"skin_fraction", &O::skin_fraction, Range::Closed(0, 1),
       "a target is a skin target when this share of its region is skin"},
      {"skin_model", &O::skin_model, "the skin model file (attend skin-train)"},
      {"skin_check", &O::skin_check,
       "a skin target's region must also be confident, skin-shaped skin"}};
  return fields;
}

std::string AttentionOptions::Check() const {
  std::string error = CheckFieldRanges(select, SelectOptions::Fields());
  if (!error.empty()) return "select." + error;
  error = CheckFieldRanges(drop, DropOptions::Fields());
  if (!error.empty()) return "drop." + error;
  error = CheckFieldRanges(inhibition, InhibitionOptions::Fields());
  if (!error.empty()) return "inhibition." + error;
  error = CheckFieldRanges(*this, Fields());
  if (!error.empty()) return error;
  error = skin_region.Check();
  if (!error.empty()) return "select.skin_region: " + error;
  error = tracker.Check();
  if (!error.empty()) return "tracker." + error;
  error = memory.Check();
  if (!error.empty()) return "attention." + error;
  return "";
}

namespace {

double MeanOver(const cv::Mat& map, const cv::Mat& mask) {
  return cv::countNonZero(mask) > 0 ? cv::mean(map, mask)[0] : 0.0;
}

cv::Point2f Centre(const cv::Rect& box) {
  return {box.x + 0.5f * box.width, box.y + 0.5f * box.height};
}

// How fast a target's velocity follows its latest displacement.
constexpr float kVelocityRate = 0.3f;
// How fast its remembered appearance follows what it looks like now.
constexpr float kAppearanceRate = 0.2f;

// A target the stage follows: its ids, counters, label and what its object file would keep.
struct Active {
  int id = 0;          // the target's id in the records
  int tracker_id = 0;  // its id in the tracker
  bool skin = false;
  int low_frames = 0;    // consecutive frames below drop.min_saliency
  int unseen = 0;        // consecutive frames not found (occluded)
  int unrecognised = 0;  // consecutive frames with detections, none on it
  int since_kept = 0;    // frames since last_box was last updated
  std::string label;     // from the top-down channels, once given
  // For its object file (object files enabled only): where it was last found and kept, how
  // fast it moved, and what it looked like.
  cv::Rect last_box;
  cv::Point2f velocity;
  ObjectAppearance appearance;
};

}  // namespace

// The stage's state across frames and its per-frame scratch.
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
  };
  // The regions of homogeneous inhibited saliency (a BIP over the inhibited saliency map) and,
  // per region, its sum, area, most salient pixel and bounds; `ranked`: the candidates,
  // (mean x area, region), best first.
  struct Candidates {
    cv::Mat labels;
    std::vector<double> sum;
    std::vector<int> area;
    std::vector<cv::Point> peak;
    std::vector<float> peak_value;
    std::vector<cv::Point> low, high;
    std::vector<std::pair<double, int>> ranked;
  };
  // What the selection of one frame keeps between its candidates.
  struct Selection {
    std::vector<std::map<int, int>> overlaps;  // per candidate: colour region -> pixels
    std::vector<uint8_t> taken;                // per colour region: a target holds it
    double max_area = 0.0;                     // select.max_area_fraction of the image
    double inhibited_area = 0.0;               // inhibited pixels, with the seeds started
    double max_inhibited = 0.0;                // select.max_inhibited_fraction of the image
    std::vector<cv::Rect> followed;            // detection seeds: the boxes followed now
  };
  // A candidate's seed: the colour regions it starts from, their area, and the detection
  // under it (-1: none), whose regions are in seed_mask_ and member_.
  struct Seed {
    int best = -1;  // the colour region under the candidate
    std::vector<int> members;
    double area = 0.0;
    int detection = -1;
  };

  void Track(const cv::Mat& bgr, const cv::Mat& skin_distance, TrackedTargets* tracked,
             const cv::Mat& cylinder);
  void Select(const Frame& in, AttentionFrame* frame);

  // Select's steps, in order.
  // The detection each found target is on (its index, -1: none), the frame's targets and
  // detections matched one to one (MatchBoxes) at IoU >= the re-anchoring threshold.
  std::vector<int> MatchDetections(const Frame& in) const;
  // The targets tracked this frame: their states and the release rules, re-anchoring on
  // their detections, their inhibition (inhibition_, covered_); ended targets are removed.
  void FollowTargets(const Frame& in, AttentionFrame* frame);
  // A found target (`result`, its `mask`, on detection `detection`): its state, release, re-anchoring and
  // inhibition; appends the tracker id to `removed` when it is released.
  void FollowFound(const Frame& in, const TrackResult& result, const cv::Mat& mask, int detection,
                   Active* active, AttendedTarget* target, std::vector<int>* removed);
  // Recognition of a found, kept target by its detection `detection` (-1: none): a detection
  // that looks like it keeps it recognised and, overlapping it partly, restarts its tracker on
  // the detection's seed; none for too long releases it as unrecognised. Returns its mask.
  cv::Mat Recognise(const Frame& in, const TrackResult& result, const cv::Mat& mask,
                    int detection, Active* active, AttendedTarget* target);
  // A kept target's inhibition (inhibition_, covered_, held_) and what its file remembers.
  void Keep(const Frame& in, const cv::Mat& own, bool duplicates, Active* active,
            AttendedTarget* target);
  // Inhibits the saliency (inhibited_); returns the inhibited pixels.
  int Inhibit(const Frame& in, AttentionFrame* frame);
  // The candidates of the inhibited saliency.
  void RankCandidates(Candidates* candidates);
  // Starts new targets on the best candidates; `looked` gets the candidates' boxes.
  void StartTargets(const Frame& in, int inhibited_pixels, AttentionFrame* frame,
                    std::vector<cv::Rect>* looked);
  // The seed of candidate `k`; false when it starts nothing.
  bool SeedOf(const Frame& in, const Candidates& candidates, size_t k, const Selection& selection,
              Seed* seed);
  // An object seed (`seed`, its best region only) grown to the proto-object around ranked
  // candidate region `r`: the colour regions mostly inside the connected area around its most
  // salient pixel whose inhibited saliency is at least seed_level times its mean, bounded as a
  // region is, then (group_min_speed) the neighbours that move alike.
  void GrowObjectSeed(const Frame& in, const Candidates& candidates, int r,
                      const Selection& selection, Seed* seed);
  // Starts a target on `seed` (a skin target when `skin`); false when its tracker does not
  // start.
  bool Start(const Frame& in, const Seed& seed, bool skin, AttentionFrame* frame);
  // Labels from the top-down channels: once given, a target keeps its label.
  void LabelTargets(const Frame& in, AttentionFrame* frame);

  // Why a found target is released this frame (kNone when it is not): SPEC 2.4's drop rule
  // and the size rules.
  ReleaseReason WhyReleased(const AttendedTarget& target, int low_frames, double shared,
                            const cv::Rect& image) const;
  // The seed of a detected object: the colour regions of `segmentation` of which at least
  // select.seed_share lies inside `box`, clipped to the box, into seed_mask_ (frame size).
  // Returns the seed's area.
  int SeedFromBox(const Segmentation& segmentation, const cv::Rect& box);
  // Leaves an object file for a target that ends.
  void Forget(const Active& active);
  // select.group_min_speed: the mean optical flow of each colour region of `segmentation`
  // from the previous frame's grey image to this one's, computed once a frame when a seed
  // first asks; false when there is no previous frame of the same size.
  bool RegionFlow(const Segmentation& segmentation);
  // Joins to `members` (colour regions) the regions next to them that move alike
  // (select.group_min_speed), not `taken`, each at most `max_area`, while `seed_area` stays
  // within it.
  void GroupByMotion(const Segmentation& segmentation, const std::vector<uint8_t>& taken,
                     double max_area, std::vector<int>* members, double* seed_area);
  // The label of the detection that overlaps `box` most (label_overlap), "" when none does.
  std::string LabelOf(const cv::Rect& box, const std::vector<Detection>& detections) const;
  // The target its tracker follows under `tracker_id`; nullptr when none.
  const Active* ActiveOfTracker(int tracker_id) const;
  Active* ActiveOfTracker(int tracker_id);

  AttentionOptions options_;
  SkinModel skin_model_;
  std::unique_ptr<TargetTracker> tracker_;
  std::vector<Active> active_;
  cv::Mat inhibition_, inhibited_;
  cv::Mat covered_;              // pixels of the active targets (masks, or boxes while occluded)
  cv::Mat held_;                 // the masks of the targets found and kept so far in this frame
  cv::Mat seed_mask_;            // an object seed's pixels
  cv::Mat fill_mask_;            // the flood fill of an object seed's salient region
  cv::Mat kernel_;               // the inhibition's dilation
  std::vector<uint8_t> member_;  // per colour region: in the object seed
  std::vector<uint8_t> detection_used_;  // per detection of the frame: a target is on it
  BipBuilder saliency_builder_;
  int attended_ = 0;
  int next_id_ = 1;  // the id the next new target gets (the tracker's own ids are internal)
  ObjectFiles files_;
  std::vector<cv::Rect> look_regions_;
  // Motion grouping: the grey frames, the flow between them and its mean per colour region.
  static constexpr int kFlowBorder = 3;  // px: a region's flow is taken this far inside it
  cv::Mat grey_, previous_grey_, flow_, border_;
  std::unique_ptr<cvextra::DenseFlow> flow_solver_;
  int flow_state_ = 0;  // this frame: 0 not computed yet, 1 computed, -1 none possible
  std::vector<cv::Point2f> region_flow_;
};

AttentionStage::Impl::Impl(const AttentionOptions& options, SkinModel skin_model, BipPool* pool)
    : options_(options),
      skin_model_(std::move(skin_model)),
      saliency_builder_(BipOptions{}, pool),
      files_(options.memory) {
  const std::string error = options_.Check();
  if (!error.empty()) throw ConfigError(error);
  tracker_ = TargetTracker::Create(options_.tracker, pool);
  // OpenCV's DIS flow is in the optional OpenCV module (util/opencv_extra.h): loaded now, so
  // that a missing module is reported before the run starts.
  if (options_.select.group_min_speed > 0.f) {
    constexpr int kDisPresetMedium = 2;  // cv::DISOpticalFlow::PRESET_MEDIUM
    flow_solver_ = cvextra::Get("select.group_min_speed (OpenCV's DIS optical flow)")
                       .CreateDisFlow(kDisPresetMedium);
  }
  const int margin = options_.inhibition.margin;
  kernel_ = cv::getStructuringElement(cv::MORPH_RECT, cv::Size(2 * margin + 1, 2 * margin + 1));
}

void AttentionStage::Impl::Track(const cv::Mat& bgr, const cv::Mat& skin_distance,
                                 TrackedTargets* tracked, const cv::Mat& cylinder) {
  const Stopwatch stopwatch;
  tracked->skin = skin_distance < skin_model_.threshold;
  tracked->results.clear();
  tracker_->Track(bgr, &tracked->results, tracked->skin, cylinder);
  tracked->milliseconds = stopwatch.ElapsedMs();
}

const Active* AttentionStage::Impl::ActiveOfTracker(int tracker_id) const {
  const auto found = std::find_if(active_.begin(), active_.end(),
                                  [&](const Active& a) { return a.tracker_id == tracker_id; });
  return found != active_.end() ? &*found : nullptr;
}

Active* AttentionStage::Impl::ActiveOfTracker(int tracker_id) {
  return const_cast<Active*>(std::as_const(*this).ActiveOfTracker(tracker_id));
}

void AttentionStage::Impl::Select(const Frame& in, AttentionFrame* frame) {
  frame->targets.clear();
  frame->new_ids.clear();
  frame->track_ms = in.tracked.milliseconds;
  files_.Age();
  if (options_.select.group_min_speed > 0.f) {
    std::swap(grey_, previous_grey_);
    cv::cvtColor(in.bgr, grey_, cv::COLOR_BGR2GRAY);
    flow_state_ = 0;
  }
  Stopwatch stage;
  FollowTargets(in, frame);
  const int inhibited_pixels = Inhibit(in, frame);
  frame->inhibit_ms = stage.ElapsedMs();

  stage.Restart();
  std::vector<cv::Rect> looked;  // the boxes of the candidates weighed, best first
  StartTargets(in, inhibited_pixels, frame, &looked);
  LabelTargets(in, frame);
  std::sort(frame->targets.begin(), frame->targets.end(),
            [](const AttendedTarget& a, const AttendedTarget& b) { return a.id < b.id; });
  frame->select_ms = stage.ElapsedMs();

  // Where attention looked: the targets followed, the objects remembered, the candidates.
  look_regions_.clear();
  for (const AttendedTarget& target : frame->targets) {
    if ((Visible(target.state) || target.state == TargetState::kOccluded) && !target.box.empty()) {
      look_regions_.push_back(target.box);
    }
  }
  for (const cv::Rect& box : files_.PredictedBoxes(in.image)) look_regions_.push_back(box);
  look_regions_.insert(look_regions_.end(), looked.begin(), looked.end());
}

std::vector<int> AttentionStage::Impl::MatchDetections(const Frame& in) const {
  // So that a target that drifted cannot take its neighbour's detection from the neighbour's
  // own target.
  std::vector<int> detection_of(in.tracked.results.size(), -1);
  if (in.detections.empty()) return detection_of;
  std::vector<int> rows;
  std::vector<cv::Rect> target_boxes, detection_boxes;
  for (size_t r = 0; r < in.tracked.results.size(); ++r) {
    const TrackResult& result = in.tracked.results[r];
    const Active* active = ActiveOfTracker(result.id);
    if (active == nullptr || active->skin || result.state != TrackState::kFound) continue;
    rows.push_back(static_cast<int>(r));
    target_boxes.push_back(result.box & in.image);
  }
  for (const Detection& detection : in.detections) detection_boxes.push_back(detection.box);
  const double min_iou =
      options_.select.reanchor_min_iou > 0.f ? options_.select.reanchor_min_iou : 0.3;
  for (const auto& [row, column] : MatchBoxes(target_boxes, detection_boxes, min_iou)) {
    detection_of[rows[row]] = column;
  }
  return detection_of;
}

void AttentionStage::Impl::FollowTargets(const Frame& in, AttentionFrame* frame) {
  inhibition_.create(in.bgr.size(), CV_32FC1);
  inhibition_.setTo(0.f);
  covered_.create(in.bgr.size(), CV_8UC1);
  covered_.setTo(0);
  detection_used_.assign(in.detections.size(), 0);
  // The pixels of the targets found and kept so far this frame, in id order: a younger
  // target most of whose mask an older one already holds is a duplicate (drop.max_shared).
  if (options_.drop.max_shared < 1.f) {
    held_.create(in.bgr.size(), CV_8UC1);
    held_.setTo(0);
  }
  const std::vector<int> detection_of = MatchDetections(in);
  std::vector<int> removed;  // tracker ids
  for (size_t r = 0; r < in.tracked.results.size(); ++r) {
    const TrackResult& result = in.tracked.results[r];
    Active* active = ActiveOfTracker(result.id);
    if (active == nullptr) continue;
    AttendedTarget target;
    target.id = active->id;
    target.box = result.box & in.image;
    target.skin = active->skin;
    const cv::Mat mask = result.state == TrackState::kFound ? tracker_->Mask(result.id) : cv::Mat();
    if (result.state == TrackState::kFound && !mask.empty()) {
      FollowFound(in, result, mask, detection_of[r], active, &target, &removed);
    } else if (result.state == TrackState::kOccluded) {
      target.state = TargetState::kOccluded;
      ++active->unseen;
      ++active->since_kept;
      target.saliency = target.box.empty() ? 0.0 : cv::mean(in.saliency(target.box))[0];
      if (options_.inhibition.keep_occluded && !target.box.empty()) {
        const cv::Rect area = options_.inhibition.occluded_search && !result.roi.empty()
                                  ? (target.box | result.roi) & in.image
                                  : target.box;
        inhibition_(area).setTo(1.f);
        covered_(area).setTo(255);
      }
    } else {
      target.state = TargetState::kLost;
      ++active->unseen;
      ++active->since_kept;
      removed.push_back(result.id);
      Forget(*active);
    }
    frame->targets.push_back(target);
  }
  for (const int id : removed) {
    tracker_->Remove(id);
    active_.erase(std::remove_if(active_.begin(), active_.end(),
                                 [id](const Active& a) { return a.tracker_id == id; }),
                  active_.end());
  }
}

cv::Mat AttentionStage::Impl::Recognise(const Frame& in, const TrackResult& result,
                                       const cv::Mat& mask, int detection, Active* active,
                                       AttendedTarget* target) {
  cv::Mat own = mask;
  int on = detection;
  const bool reanchor = on >= 0 && options_.select.reanchor_min_iou > 0.f &&
                        BoxIou(target->box, in.detections[on].box) <
                            options_.select.reanchor_max_iou;
  const int seed_area = reanchor ? SeedFromBox(in.segmentation, in.detections[on].box) : 0;
  if (reanchor && options_.select.reanchor_min_similarity > 0.f &&
      !active->appearance.empty() && seed_area > 0 &&
      active->appearance.Similarity(
          ObjectAppearance::Of(in.bgr, seed_mask_, in.detections[on].box)) <
          options_.select.reanchor_min_similarity) {
    on = -1;  // the detection is someone else's: this target is not recognised
  }
  if (on >= 0) {
    detection_used_[on] = 1;
    active->unrecognised = 0;
    if (reanchor && seed_area >= options_.select.min_area) {
      const int restarted = tracker_->StartFromMask(in.bgr, seed_mask_, TrackSimilarity::kColour,
                                                    in.tracked.skin);
      if (restarted >= 0) {
        tracker_->Remove(result.id);
        active->tracker_id = restarted;
        own = tracker_->Mask(restarted);
        target->box = cv::boundingRect(own) & in.image;
        target->area = cv::countNonZero(own);
      }
    }
  } else if (!active->label.empty() && options_.drop.unrecognised_frames > 0 &&
             ++active->unrecognised >= options_.drop.unrecognised_frames) {
    target->reason = ReleaseReason::kUnrecognised;
  }
  return own;
}

void AttentionStage::Impl::Keep(const Frame& in, const cv::Mat& own, bool duplicates,
                                Active* active, AttendedTarget* target) {
  // Inhibit the mask, dilated, within its box plus the margin.
  const int margin = options_.inhibition.margin;
  const cv::Rect around = cv::Rect(target->box.x - margin, target->box.y - margin,
                                   target->box.width + 2 * margin,
                                   target->box.height + 2 * margin) &
                          in.image;
  cv::Mat grown;
  cv::dilate(own(around), grown, kernel_);
  inhibition_(around).setTo(1.f, grown);
  covered_.setTo(255, own);
  if (duplicates) held_.setTo(255, own);
  // Its file remembers it as it was last seen on its object: with top-down channels, a
  // labelled target only in the frames a detection is on it (its tracker may drift in the
  // others). Its appearance serves the re-anchoring's gate as well as the object files.
  ++active->since_kept;
  const bool appearances = files_.enabled() || options_.select.reanchor_min_similarity > 0.f;
  const bool recognised =
      in.detections.empty() || active->label.empty() || active->unrecognised == 0;
  if (appearances && recognised) {
    if (!active->last_box.empty()) {
      const cv::Point2f moved = Centre(target->box) - Centre(active->last_box);
      const float steps = static_cast<float>(active->since_kept);
      active->velocity += kVelocityRate * (moved / steps - active->velocity);
    }
    active->last_box = target->box;
    active->since_kept = 0;
    active->appearance.Blend(ObjectAppearance::Of(in.bgr, own, target->box), kAppearanceRate);
  }
  active->unseen = 0;
}

void AttentionStage::Impl::FollowFound(const Frame& in, const TrackResult& result,
                                       const cv::Mat& mask, int detection, Active* active,
                                       AttendedTarget* target, std::vector<int>* removed) {
  const bool duplicates = options_.drop.max_shared < 1.f;
  target->state = TargetState::kTracked;
  target->area = result.area;
  target->saliency = MeanOver(in.saliency, mask);
  active->low_frames = target->saliency < options_.drop.min_saliency ? active->low_frames + 1 : 0;
  const double shared = duplicates && result.area > 0
                            ? static_cast<double>(cv::countNonZero(held_ & mask)) / result.area
                            : 0.0;
  target->reason = WhyReleased(*target, active->low_frames, shared, in.image);
  const cv::Mat own = target->reason == ReleaseReason::kNone && !in.detections.empty() &&
                              !active->skin
                          ? Recognise(in, result, mask, detection, active, target)
                          : mask;
  // Released targets inhibit nothing, from the frame they are released in.
  if (target->reason != ReleaseReason::kNone) {
    target->state = TargetState::kReleased;
    removed->push_back(active->tracker_id);
    // A duplicate's object is another target's; any other release ends the object's
    // tracking, not the object (its file keeps the last box it was kept with).
    if (target->reason != ReleaseReason::kDuplicate) Forget(*active);
    return;
  }
  Keep(in, own, duplicates, active, target);
}

int AttentionStage::Impl::Inhibit(const Frame& in, AttentionFrame* frame) {
  // A remembered object's inhibition follows its predicted box and fades.
  files_.Inhibit(&inhibition_);
  cv::subtract(cv::Scalar(1.f), inhibition_, inhibited_);
  cv::multiply(in.saliency, inhibited_, inhibited_);
  const int inhibited_pixels = cv::countNonZero(inhibition_);
  frame->inhibited_fraction = static_cast<double>(inhibited_pixels) / inhibition_.total();
  return inhibited_pixels;
}

void AttentionStage::Impl::RankCandidates(Candidates* c) {
  cv::Mat scaled, features;
  inhibited_.convertTo(scaled, CV_32F, 255.0);
  const cv::Mat zero = cv::Mat::zeros(scaled.size(), CV_32FC1);
  cv::merge(std::vector<cv::Mat>{scaled, zero, zero}, features);
  const Bip& bip = saliency_builder_.Build(features, HsvSimilarity(options_.select.saliency_t_max));
  const int count = bip.LabelRoots(&c->labels);
  saliency_builder_.Release();  // its levels serve the other pyramids of the frame
  c->sum.assign(count, 0.0);
  c->area.assign(count, 0);
  c->peak.assign(count, cv::Point());
  c->peak_value.assign(count, -1.f);
  c->low.assign(count, {c->labels.cols, c->labels.rows});
  c->high.assign(count, {-1, -1});
  // A row at a time, a run of one label at a time: the sums, peaks and extents are taken
  // in the same order as pixel by pixel, so they are the same, at a fraction of the cost.
  for (int y = 0; y < c->labels.rows; ++y) {
    const int* label = c->labels.ptr<int>(y);
    const float* s = inhibited_.ptr<float>(y);
    for (int x = 0; x < c->labels.cols;) {
      const int r = label[x];
      const int first = x;
      while (x < c->labels.cols && label[x] == r) ++x;
      if (r < 0) continue;
      double& sum = c->sum[r];
      float& peak = c->peak_value[r];
      for (int i = first; i < x; ++i) {
        sum += s[i];
        if (s[i] > peak) peak = s[i], c->peak[r] = {i, y};
      }
      c->area[r] += x - first;
      c->low[r] = {std::min(c->low[r].x, first), std::min(c->low[r].y, y)};
      c->high[r] = {std::max(c->high[r].x, x - 1), std::max(c->high[r].y, y)};
    }
  }
  c->ranked.clear();
  for (int r = 0; r < count; ++r) {
    const double mean = c->area[r] > 0 ? c->sum[r] / c->area[r] : 0.0;
    if (mean >= options_.select.min_saliency && c->area[r] >= options_.select.min_area) {
      c->ranked.push_back({mean * c->area[r], r});
    }
  }
  std::stable_sort(c->ranked.begin(), c->ranked.end(),
                   [](const auto& a, const auto& b) { return a.first > b.first; });
}

void AttentionStage::Impl::StartTargets(const Frame& in, int inhibited_pixels,
                                        AttentionFrame* frame, std::vector<cv::Rect>* looked) {
  const int free_slots = options_.select.max_targets - static_cast<int>(active_.size());
  if (free_slots <= 0) return;
  Candidates c;
  RankCandidates(&c);
  for (size_t k = 0; k < c.ranked.size() && k < kLookCandidates; ++k) {
    const int r = c.ranked[k].second;
    looked->push_back(cv::Rect(c.low[r], c.high[r] + cv::Point(1, 1)));
  }
  if (c.ranked.empty()) return;

  // The colour regions under each candidate, and those an active target covers.
  Selection selection;
  std::vector<int> candidate_of(c.sum.size(), -1);
  for (size_t k = 0; k < c.ranked.size(); ++k) candidate_of[c.ranked[k].second] = static_cast<int>(k);
  selection.overlaps.resize(c.ranked.size());
  const cv::Mat& colour = in.segmentation.labels;
  selection.taken.assign(in.segmentation.regions.size(), 0);
  for (int y = 0; y < c.labels.rows; ++y) {
    const int* label = c.labels.ptr<int>(y);
    const int* region = colour.ptr<int>(y);
    const uchar* covered = covered_.ptr<uchar>(y);
    for (int x = 0; x < c.labels.cols; ++x) {
      if (region[x] < 0) continue;
      if (covered[x]) selection.taken[region[x]] = 1;
      if (label[x] >= 0 && candidate_of[label[x]] >= 0) {
        ++selection.overlaps[candidate_of[label[x]]][region[x]];
      }
    }
  }
  selection.max_area = options_.select.max_area_fraction * in.bgr.total();
  // New targets are started only while the inhibition stays within
  // select.max_inhibited_fraction of the image: attention that covers everything attends
  // nothing (each new region counts with its own area).
  selection.inhibited_area = inhibited_pixels;
  selection.max_inhibited = options_.select.max_inhibited_fraction * in.bgr.total();
  // The boxes of the targets followed now: a detection they already cover is attended.
  if (options_.select.seed == SeedKind::kDetection) {
    for (const AttendedTarget& t : frame->targets) {
      if (t.state == TargetState::kTracked || t.state == TargetState::kOccluded) {
        selection.followed.push_back(t.box);
      }
    }
  }
  int started = 0;
  for (size_t k = 0; k < c.ranked.size(); ++k) {
    if (started >= std::min(options_.select.max_new, free_slots)) break;
    Seed seed;
    if (!SeedOf(in, c, k, selection, &seed)) continue;
    if (selection.inhibited_area + seed.area > selection.max_inhibited) continue;
    const cv::Mat region_mask = colour == seed.best;
    const double region_area = in.segmentation.regions[seed.best].area;
    const double skin_share =
        static_cast<double>(cv::countNonZero(in.tracked.skin & region_mask)) / region_area;
    // A mostly-skin region is a skin target only when it is confident, skin-shaped skin
    // (features/skin.h, JudgeSkinRegion), unless skin_check is off (the thesis's rule).
    // A skin target is its skin region alone, whatever the seed.
    const bool skin =
        skin_share >= options_.skin_fraction &&
        (!options_.skin_check || JudgeSkinRegion(region_mask, in.skin_distance,
                                                 skin_model_.threshold, options_.skin_region)
                                     .skin);
    if (skin) seed.members.resize(1), seed.area = region_area;
    selection.inhibited_area += seed.area;
    for (const int region : seed.members) selection.taken[region] = 1;
    if (seed.detection >= 0 && !skin) {
      for (int region = 0; region < static_cast<int>(member_.size()); ++region) {
        if (member_[region]) selection.taken[region] = 1;
      }
      detection_used_[seed.detection] = 1;
    }
    if (Start(in, seed, skin, frame)) ++started;
  }
}

void AttentionStage::Impl::GrowObjectSeed(const Frame& in, const Candidates& c, int r,
                                          const Selection& selection, Seed* seed) {
  const Segmentation& segmentation = in.segmentation;
  const int best = seed->best;
  const cv::Mat& colour = segmentation.labels;
  std::map<int, int> inside;  // colour region -> its pixels in the proto-object
  const float level =
      static_cast<float>(options_.select.seed_level * c.sum[r] / std::max(1, c.area[r]));
  fill_mask_.create(inhibited_.rows + 2, inhibited_.cols + 2, CV_8UC1);
  fill_mask_.setTo(0);
  cv::Rect filled;
  const float from = std::min(level, c.peak_value[r]);
  cv::floodFill(inhibited_, fill_mask_, c.peak[r], cv::Scalar(), &filled,
                cv::Scalar(c.peak_value[r] - from), cv::Scalar(1e6),
                4 | cv::FLOODFILL_FIXED_RANGE | cv::FLOODFILL_MASK_ONLY | (255 << 8));
  for (int y = filled.y; y < filled.y + filled.height; ++y) {
    const int* region = colour.ptr<int>(y);
    const uchar* mark = fill_mask_.ptr<uchar>(y + 1) + 1;
    for (int x = filled.x; x < filled.x + filled.width; ++x) {
      if (mark[x] && region[x] >= 0) ++inside[region[x]];
    }
  }
  for (const auto& [region, pixels] : inside) {
    const int region_area = segmentation.regions[region].area;
    if (region == best || selection.taken[region] || region_area > selection.max_area ||
        pixels < options_.select.seed_share * region_area) {
      continue;
    }
    seed->members.push_back(region);
    seed->area += region_area;
  }
  if (seed->area > selection.max_area) {
    seed->members.resize(1);
    seed->area = segmentation.regions[best].area;
  }
  if (options_.select.group_min_speed > 0.f) {
    GroupByMotion(segmentation, selection.taken, selection.max_area, &seed->members, &seed->area);
  }
}

bool AttentionStage::Impl::SeedOf(const Frame& in, const Candidates& c, size_t k,
                                  const Selection& selection, Seed* seed) {
  const Segmentation& segmentation = in.segmentation;
  int best = -1, best_count = 0;
  for (const auto& [region, pixels] : selection.overlaps[k]) {
    if (pixels > best_count) best = region, best_count = pixels;
  }
  if (best < 0 || selection.taken[best] || segmentation.regions[best].area > selection.max_area) {
    return false;
  }
  const int r = c.ranked[k].second;
  const bool detection_seed = options_.select.seed == SeedKind::kDetection;
  const bool object_seed = options_.select.seed == SeedKind::kObject || detection_seed;
  // The detection under the candidate's most salient pixel, if any (the most confident).
  const Detection* under = nullptr;
  int under_index = -1;
  if (detection_seed) {
    for (size_t d = 0; d < in.detections.size(); ++d) {
      const Detection& detection = in.detections[d];
      if (detection.box.contains(c.peak[r]) &&
          (under == nullptr || detection.confidence > under->confidence)) {
        under = &detection, under_index = static_cast<int>(d);
      }
    }
  }
  // A detection a target is on (or was started on this frame) is attended already.
  if (under != nullptr && detection_used_[under_index]) return false;
  if (detection_seed && under == nullptr && options_.select.detected_only) return false;
  if (under != nullptr) {
    // Part of an object already followed (the legs of a person whose upper body is a
    // target): inhibited, as the object is.
    for (const cv::Rect& box : selection.followed) {
      const int shared = (box & under->box).area();
      if (shared > 0 && shared >= options_.select.detection_taken * under->box.area()) return false;
    }
  }
  // The seed: the best region alone, or with the regions mostly inside the candidate.
  seed->best = best;
  seed->members = {best};
  seed->area = segmentation.regions[best].area;
  seed->detection = under_index;
  if (under != nullptr) {
    // A whole object: the colour regions mostly inside the detection's box, clipped to it
    // (the pavement under a person's feet stays out).
    seed->area = SeedFromBox(segmentation, under->box);
    return seed->area >= options_.select.min_area && seed->area <= selection.max_area;
  }
  if (!object_seed) return true;
  GrowObjectSeed(in, c, r, selection, seed);
  return true;
}

bool AttentionStage::Impl::Start(const Frame& in, const Seed& seed, bool skin,
                                 AttentionFrame* frame) {
  const cv::Mat& colour = in.segmentation.labels;
  int tracker_id = -1;
  if (seed.detection >= 0 && !skin) {
    tracker_id =
        tracker_->StartFromMask(in.bgr, seed_mask_, TrackSimilarity::kColour, in.tracked.skin);
  } else if (seed.members.size() == 1) {
    tracker_id = tracker_->StartFromRegion(
        in.bgr, colour, seed.best, skin ? TrackSimilarity::kSkin : TrackSimilarity::kColour,
        in.tracked.skin);
  } else {
    member_.assign(in.segmentation.regions.size(), 0);
    for (const int region : seed.members) member_[region] = 1;
    seed_mask_.create(colour.size(), CV_8UC1);
    for (int y = 0; y < colour.rows; ++y) {
      const int* region = colour.ptr<int>(y);
      uchar* out = seed_mask_.ptr<uchar>(y);
      for (int x = 0; x < colour.cols; ++x) {
        out[x] = region[x] >= 0 && member_[region[x]] ? 255 : 0;
      }
    }
    tracker_id =
        tracker_->StartFromMask(in.bgr, seed_mask_, TrackSimilarity::kColour, in.tracked.skin);
  }
  if (tracker_id < 0) return false;
  const cv::Mat own = tracker_->Mask(tracker_id);
  AttendedTarget target;
  target.box = cv::boundingRect(own);
  target.area = cv::countNonZero(own);
  target.saliency = MeanOver(in.saliency, own);
  target.state = TargetState::kNew;
  target.skin = skin;
  Active active;
  active.tracker_id = tracker_id;
  active.skin = skin;
  if (files_.enabled()) {
    // A remembered object attended again resumes its id, its label and its motion.
    active.last_box = target.box;
    active.appearance = ObjectAppearance::Of(in.bgr, own, target.box);
    const int file = files_.Match(target.box, active.appearance, skin);
    if (file >= 0) {
      ObjectFile resumed = files_.Take(file);
      active.id = resumed.id;
      active.label = resumed.label;
      active.velocity = resumed.velocity;
      resumed.appearance.Blend(active.appearance, kAppearanceRate);
      active.appearance = resumed.appearance;
      target.state = TargetState::kResumed;
      // Its file counts the frames since it was last seen, this one included.
      target.absent_frames = resumed.absent - 1;
    }
  }
  if (target.state == TargetState::kNew) {
    active.id = next_id_++;
    ++attended_;
    frame->new_ids.push_back(active.id);
  }
  target.id = active.id;
  active_.push_back(active);
  frame->targets.push_back(target);
  return true;
}

void AttentionStage::Impl::LabelTargets(const Frame& in, AttentionFrame* frame) {
  if (!in.detections.empty()) {
    for (AttendedTarget& target : frame->targets) {
      if (!Visible(target.state)) continue;
      auto active = std::find_if(active_.begin(), active_.end(),
                                 [&](const Active& a) { return a.id == target.id; });
      if (active == active_.end() || !active->label.empty()) continue;
      active->label = LabelOf(target.box, in.detections);
    }
  }
  for (AttendedTarget& target : frame->targets) {
    auto active = std::find_if(active_.begin(), active_.end(),
                               [&](const Active& a) { return a.id == target.id; });
    if (active != active_.end()) target.label = active->label;
  }
}

int AttentionStage::Impl::SeedFromBox(const Segmentation& segmentation, const cv::Rect& box_in) {
  const cv::Mat& colour = segmentation.labels;
  const cv::Rect box = box_in & cv::Rect(0, 0, colour.cols, colour.rows);
  seed_mask_.create(colour.size(), CV_8UC1);
  seed_mask_.setTo(0);
  if (box.empty()) return 0;
  std::map<int, int> inside;
  for (int y = box.y; y < box.y + box.height; ++y) {
    const int* region = colour.ptr<int>(y);
    for (int x = box.x; x < box.x + box.width; ++x) {
      if (region[x] >= 0) ++inside[region[x]];
    }
  }
  member_.assign(segmentation.regions.size(), 0);
  for (const auto& [region, pixels] : inside) {
    if (pixels >= options_.select.seed_share * segmentation.regions[region].area) {
      member_[region] = 1;
    }
  }
  int area = 0;
  for (int y = box.y; y < box.y + box.height; ++y) {
    const int* region = colour.ptr<int>(y);
    uchar* out = seed_mask_.ptr<uchar>(y);
    for (int x = box.x; x < box.x + box.width; ++x) {
      if (region[x] >= 0 && member_[region[x]]) out[x] = 255, ++area;
    }
  }
  return area;
}

bool AttentionStage::Impl::RegionFlow(const Segmentation& segmentation) {
  if (flow_state_ != 0) return flow_state_ > 0;
  flow_state_ = -1;
  if (previous_grey_.empty() || previous_grey_.size() != grey_.size()) return false;
  ATTEND_CHECK(flow_solver_ != nullptr) << "motion grouping without its flow";
  flow_solver_->Calc(previous_grey_, grey_, &flow_);
  // The flow bleeds across the edges of what moves (the solver smooths it), so a region's flow
  // is its mean away from its border, kFlowBorder px in; a region that is all border keeps all
  // its pixels.
  const cv::Mat& labels = segmentation.labels;
  border_.create(labels.size(), CV_8UC1);
  border_.setTo(0);
  for (int y = 0; y < labels.rows; ++y) {
    const int* label = labels.ptr<int>(y);
    const int* below = y + 1 < labels.rows ? labels.ptr<int>(y + 1) : nullptr;
    uchar* edge = border_.ptr<uchar>(y);
    uchar* edge_below = below != nullptr ? border_.ptr<uchar>(y + 1) : nullptr;
    for (int x = 0; x < labels.cols; ++x) {
      if (x + 1 < labels.cols && label[x + 1] != label[x]) edge[x] = edge[x + 1] = 255;
      if (below != nullptr && below[x] != label[x]) edge[x] = edge_below[x] = 255;
    }
  }
  cv::dilate(border_, border_,
             cv::getStructuringElement(cv::MORPH_RECT,
                                       cv::Size(2 * kFlowBorder + 1, 2 * kFlowBorder + 1)));
  const size_t regions = segmentation.regions.size();
  std::vector<cv::Point2d> inner_sum(regions), all_sum(regions);
  std::vector<int> inner_count(regions, 0), all_count(regions, 0);
  for (int y = 0; y < flow_.rows; ++y) {
    const int* label = labels.ptr<int>(y);
    const uchar* edge = border_.ptr<uchar>(y);
    const cv::Point2f* flow = flow_.ptr<cv::Point2f>(y);
    for (int x = 0; x < flow_.cols; ++x) {
      if (label[x] < 0) continue;
      const cv::Point2d pixel(flow[x].x, flow[x].y);
      all_sum[label[x]] += pixel;
      ++all_count[label[x]];
      if (!edge[x]) inner_sum[label[x]] += pixel, ++inner_count[label[x]];
    }
  }
  region_flow_.assign(regions, cv::Point2f());
  for (size_t r = 0; r < regions; ++r) {
    if (inner_count[r] > 0) {
      region_flow_[r] = cv::Point2f(inner_sum[r] * (1.0 / inner_count[r]));
    } else if (all_count[r] > 0) {
      region_flow_[r] = cv::Point2f(all_sum[r] * (1.0 / all_count[r]));
    }
  }
  flow_state_ = 1;
  return true;
}

void AttentionStage::Impl::GroupByMotion(const Segmentation& segmentation,
                                         const std::vector<uint8_t>& taken, double max_area,
                                         std::vector<int>* members, double* seed_area) {
  if (!RegionFlow(segmentation)) return;
  // The proto-object's motion: its regions' flows weighted by their areas.
  cv::Point2d motion;
  double area = 0.0;
  for (const int region : *members) {
    motion += cv::Point2d(region_flow_[region]) * segmentation.regions[region].area;
    area += segmentation.regions[region].area;
  }
  if (area <= 0.0) return;
  motion *= 1.0 / area;
  const double speed = cv::norm(motion);
  if (speed < options_.select.group_min_speed) return;
  const double tolerance = options_.select.group_flow_tolerance * speed;
  std::vector<uint8_t> in(segmentation.regions.size(), 0);
  for (const int region : *members) in[region] = 1;
  // Outwards from the proto-object, a region at a time (breadth first).
  for (size_t next = 0; next < members->size(); ++next) {
    const int region = (*members)[next];
    const RegionAdjacency& adjacency = segmentation.adjacency;
    for (const int* at = adjacency.NeighboursBegin(region); at != adjacency.NeighboursEnd(region);
         ++at) {
      const int neighbour = *at;
      if (in[neighbour] || taken[neighbour]) continue;
      const int neighbour_area = segmentation.regions[neighbour].area;
      if (neighbour_area > max_area || *seed_area + neighbour_area > max_area) continue;
      if (cv::norm(cv::Point2d(region_flow_[neighbour]) - motion) > tolerance) continue;
      in[neighbour] = 1;
      members->push_back(neighbour);
      *seed_area += neighbour_area;
    }
  }
}

void AttentionStage::Impl::Forget(const Active& active) {
  if (!files_.enabled() || active.last_box.empty()) return;
  ObjectFile file;
  file.id = active.id;
  file.box = active.last_box;
  file.velocity = active.velocity;
  file.absent = active.since_kept;
  file.appearance = active.appearance;
  file.skin = active.skin;
  file.label = active.label;
  files_.Remember(std::move(file));
}

std::string AttentionStage::Impl::LabelOf(const cv::Rect& box,
                                          const std::vector<Detection>& detections) const {
  std::string label;
  double best = options_.label_overlap;
  for (const Detection& detection : detections) {
    // Of both boxes: a target on half a person is labelled by the person's detection, a box
    // on the pavement that one detection crosses is not.
    const int larger = std::max(box.area(), detection.box.area());
    const double overlap =
        larger > 0 ? static_cast<double>((box & detection.box).area()) / larger : 0.0;
    if (overlap >= best && !detection.label.empty()) best = overlap, label = detection.label;
  }
  return label;
}

ReleaseReason AttentionStage::Impl::WhyReleased(const AttendedTarget& target, int low_frames,
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
                            const std::vector<Detection>& detections) {
  // Maps of the last frame that someone still holds are let go (util/shared_mat.h).
  ReleaseIfShared(&impl_->inhibition_);
  ReleaseIfShared(&impl_->inhibited_);
  impl_->Select({bgr, skin_distance, tracked, saliency, segmentation, detections,
                 cv::Rect(0, 0, bgr.cols, bgr.rows)},
                frame);
}

const std::vector<cv::Rect>& AttentionStage::look_regions() const { return impl_->look_regions_; }
const ObjectFiles& AttentionStage::object_files() const { return impl_->files_; }
const cv::Mat& AttentionStage::inhibition() const { return impl_->inhibition_; }
const cv::Mat& AttentionStage::inhibited() const { return impl_->inhibited_; }
int AttentionStage::targets_attended() const { return impl_->attended_; }
const char* AttentionStage::tracker_name() const { return impl_->tracker_->name(); }

}  // namespace attend
