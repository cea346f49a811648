#include "semiattentive/seeds.h"

#include <algorithm>
#include <opencv2/imgproc.hpp>

namespace attend {

namespace {

// The detection whose box holds `point`, the most confident; -1 when none does.
int DetectionUnder(const std::vector<Detection>& detections, const cv::Point& point) {
  const Detection* under = nullptr;
  int index = -1;
  for (size_t d = 0; d < detections.size(); ++d) {
    const Detection& detection = detections[d];
    if (detection.box.contains(point) &&
        (under == nullptr || detection.confidence > under->confidence)) {
      under = &detection, index = static_cast<int>(d);
    }
  }
  return index;
}

}  // namespace

bool SeedMaker::Make(const SeedFrame& frame, size_t k, MotionGrouping* grouping, Seed* seed) {
  const Segmentation& segmentation = frame.segmentation;
  int best = -1, best_count = 0;
  for (const auto& [region, pixels] : frame.under.overlaps[k]) {
    if (pixels > best_count) best = region, best_count = pixels;
  }
  if (best < 0 || frame.under.taken[best] || segmentation.regions[best].area > frame.max_area) {
    return false;
  }
  const int r = frame.candidates.ranked[k].second;
  const bool detection_seed = options_.seed == SeedKind::kDetection;
  const bool object_seed = options_.seed == SeedKind::kObject || detection_seed;
  // The detection under the candidate's most salient pixel, if any.
  const int under =
      detection_seed ? DetectionUnder(frame.detections, frame.candidates.peak[r]) : -1;
  // A detection a target is on (or was started on this frame) is attended already.
  if (under >= 0 && frame.detection_used[under]) return false;
  if (detection_seed && under < 0 && options_.detected_only) return false;
  if (under >= 0) {
    // Part of an object already followed (the legs of a person whose upper body is a
    // target): inhibited, as the object is.
    const cv::Rect& box = frame.detections[under].box;
    for (const cv::Rect& followed : frame.followed) {
      const int shared = (followed & box).area();
      if (shared > 0 && shared >= options_.detection_taken * box.area()) return false;
    }
  }
  // The seed: the best region alone, or with the regions mostly inside the candidate.
  seed->best = best;
  seed->members = {best};
  seed->area = segmentation.regions[best].area;
  seed->detection = under;
  if (under >= 0) {
    // A whole object: the colour regions mostly inside the detection's box, clipped to it
    // (the pavement under a person's feet stays out).
    FromBox(segmentation, frame.detections[under].box, seed);
    return seed->area >= options_.min_area && seed->area <= frame.max_area;
  }
  // A region seed stays one region: grouping it by depth alone joined touching objects at one
  // depth on the bundled crowd scene (a revisit), where the object seed's salient area keeps
  // them apart (docs/ATTENTION.md, "Background and proto-objects").
  if (object_seed) GrowObject(frame, r, grouping, seed);
  return true;
}

bool SeedMaker::FromDetection(const SeedFrame& frame, int index, Seed* seed) {
  if (frame.detection_used[index]) return false;
  const cv::Rect& box = frame.detections[index].box;
  for (const cv::Rect& followed : frame.followed) {
    const int shared = (followed & box).area();
    if (shared > 0 && shared >= options_.detection_taken * box.area()) return false;
  }
  seed->members.clear();
  FromBox(frame.segmentation, box, seed);
  if (seed->members.empty()) return false;
  seed->best = seed->members.front();
  seed->detection = index;
  for (const int region : seed->members) {
    if (region < static_cast<int>(frame.under.taken.size()) && frame.under.taken[region]) {
      return false;
    }
  }
  // Bounded by the detection's box, which the detector says is one object, not by the
  // background rule of select.max_area_fraction: a person near the camera is large.
  return seed->area >= options_.min_area;
}

void SeedMaker::GrowObject(const SeedFrame& frame, int r, MotionGrouping* grouping, Seed* seed) {
  const Segmentation& segmentation = frame.segmentation;
  const Candidates& c = frame.candidates;
  const cv::Mat& colour = segmentation.labels;
  std::map<int, int> inside;  // colour region -> its pixels in the proto-object
  const float level = static_cast<float>(options_.seed_level * c.sum[r] / std::max(1, c.area[r]));
  fill_.create(frame.inhibited.rows + 2, frame.inhibited.cols + 2, CV_8UC1);
  fill_.setTo(0);
  cv::Rect filled;
  const float from = std::min(level, c.peak_value[r]);
  cv::floodFill(frame.inhibited, fill_, c.peak[r], cv::Scalar(), &filled,
                cv::Scalar(c.peak_value[r] - from), cv::Scalar(1e6),
                4 | cv::FLOODFILL_FIXED_RANGE | cv::FLOODFILL_MASK_ONLY | (255 << 8));
  for (int y = filled.y; y < filled.y + filled.height; ++y) {
    const int* region = colour.ptr<int>(y);
    const uchar* mark = fill_.ptr<uchar>(y + 1) + 1;
    for (int x = filled.x; x < filled.x + filled.width; ++x) {
      if (mark[x] && region[x] >= 0) ++inside[region[x]];
    }
  }
  const std::vector<uint8_t>& taken = frame.under.taken;
  for (const auto& [region, pixels] : inside) {
    const int region_area = segmentation.regions[region].area;
    if (region == seed->best || taken[region] || region_area > frame.max_area ||
        pixels < options_.seed_share * region_area) {
      continue;
    }
    seed->members.push_back(region);
    seed->area += region_area;
  }
  if (seed->area > frame.max_area) {
    seed->members.resize(1);
    seed->area = segmentation.regions[seed->best].area;
  }
  // Stereo: the neighbours at the seed's depth join it (one object at one depth).
  if (frame.scene != nullptr) {
    frame.scene->GroupByDepth(segmentation, taken, frame.max_area, &seed->members, &seed->area);
  }
  if (grouping != nullptr) {
    grouping->Group(segmentation, taken, frame.max_area, &seed->members, &seed->area);
  }
}

void SeedMaker::FromBox(const Segmentation& segmentation, const cv::Rect& box_in, Seed* seed) {
  const cv::Mat& colour = segmentation.labels;
  const cv::Rect box = box_in & cv::Rect(0, 0, colour.cols, colour.rows);
  mask_.create(colour.size(), CV_8UC1);
  mask_.setTo(0);
  seed->mask = mask_;
  seed->area = 0;
  if (box.empty()) return;
  std::map<int, int> inside;
  for (int y = box.y; y < box.y + box.height; ++y) {
    const int* region = colour.ptr<int>(y);
    for (int x = box.x; x < box.x + box.width; ++x) {
      if (region[x] >= 0) ++inside[region[x]];
    }
  }
  member_.assign(segmentation.regions.size(), 0);
  for (const auto& [region, pixels] : inside) {
    if (pixels >= options_.seed_share * segmentation.regions[region].area) {
      member_[region] = 1;
      if (region != seed->best) seed->members.push_back(region);
    }
  }
  int area = 0;
  for (int y = box.y; y < box.y + box.height; ++y) {
    const int* region = colour.ptr<int>(y);
    uchar* out = mask_.ptr<uchar>(y);
    for (int x = box.x; x < box.x + box.width; ++x) {
      if (region[x] >= 0 && member_[region[x]]) out[x] = 255, ++area;
    }
  }
  seed->area = area;
}

const cv::Mat& SeedMaker::MaskOf(const Segmentation& segmentation,
                                 const std::vector<int>& members) {
  const cv::Mat& colour = segmentation.labels;
  member_.assign(segmentation.regions.size(), 0);
  for (const int region : members) member_[region] = 1;
  mask_.create(colour.size(), CV_8UC1);
  for (int y = 0; y < colour.rows; ++y) {
    const int* region = colour.ptr<int>(y);
    uchar* out = mask_.ptr<uchar>(y);
    for (int x = 0; x < colour.cols; ++x) out[x] = region[x] >= 0 && member_[region[x]] ? 255 : 0;
  }
  return mask_;
}

}  // namespace attend
