#include "app/detection_tracks.h"

#include <utility>

#include "util/assignment.h"
#include "util/error.h"

namespace attend {

const OptionFields<DetectionLinkOptions>& DetectionLinkOptions::Fields() {
  using O = DetectionLinkOptions;
  static const OptionFields<DetectionLinkOptions> fields = {
      {"match_iou", &O::match_iou, Range::AboveUpTo(0, 1),
       "a track and a detection pair only at IoU >= this"},
      {"max_missed", &O::max_missed, Range::Closed(0, 100000),
       "a track unmatched for more than this many frames in a row ends"},
      {"velocity_frames", &O::velocity_frames, Range::Closed(0, 1000),
       "the velocity is the mean displacement over this many matched frames; 0: none"}};
  return fields;
}

std::string DetectionLinkOptions::Check() const { return CheckFieldRanges(*this, Fields()); }

DetectionLinker::DetectionLinker(const DetectionLinkOptions& options) : options_(options) {
  const std::string error = options_.Check();
  ATTEND_CHECK(error.empty()) << error;
}

cv::Rect2d DetectionLinker::Predict(const Track& track, int frame) const {
  const auto& [last_frame, last] = track.seen.back();
  const auto& [first_frame, first] = track.seen.front();
  if (last_frame == first_frame) return last;
  // The centre's mean displacement a frame; the corner moves as the centre does.
  const double frames = static_cast<double>(last_frame - first_frame);
  const double vx = ((last.x + 0.5 * last.width) - (first.x + 0.5 * first.width)) / frames;
  const double vy = ((last.y + 0.5 * last.height) - (first.y + 0.5 * first.height)) / frames;
  const double ahead = static_cast<double>(frame - last_frame);
  return {last.x + vx * ahead, last.y + vy * ahead, last.width, last.height};
}

std::vector<LinkedBox> DetectionLinker::Link(const std::vector<cv::Rect>& detections) {
  ++frame_;
  // Tracks unmatched for more than max_missed frames end before the match: a track last
  // matched in frame f may still match in frame f + max_missed + 1.
  std::erase_if(tracks_, [&](const Track& track) {
    return frame_ - track.seen.back().first - 1 > options_.max_missed;
  });
  std::vector<cv::Rect2d> predicted, found;
  predicted.reserve(tracks_.size());
  for (const Track& track : tracks_) predicted.push_back(Predict(track, frame_));
  found.reserve(detections.size());
  for (const cv::Rect& box : detections) found.emplace_back(box);

  std::vector<LinkedBox> linked(detections.size());
  std::vector<bool> paired(detections.size(), false);
  for (const auto& [t, d] : MatchBoxes(predicted, found, options_.match_iou)) {
    Track& track = tracks_[t];
    track.seen.emplace_back(frame_, found[d]);
    while (static_cast<int>(track.seen.size()) > options_.velocity_frames + 1) {
      track.seen.pop_front();
    }
    linked[d] = {track.id, detections[d], false, d};
    paired[d] = true;
  }
  for (size_t d = 0; d < detections.size(); ++d) {
    if (paired[d]) continue;
    Track track;
    track.id = next_id_++;
    track.seen.emplace_back(frame_, found[d]);
    tracks_.push_back(std::move(track));
    linked[d] = {tracks_.back().id, detections[d], true, static_cast<int>(d)};
  }
  return linked;
}

}  // namespace attend
