#include "pipeline/frame_record.h"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "util/error.h"
#include "util/json_text.h"

namespace attend {

namespace {

// [begin, end) of one axis from working into input pixels, clipped to [0, limit].
void InputFromWorkingSpan(int begin, int length, double scale, int limit, int* out_begin,
                          int* out_length) {
  int first = static_cast<int>(std::lround(begin / scale));
  int last = static_cast<int>(std::lround((begin + length) / scale));
  first = std::clamp(first, 0, limit);
  last = std::clamp(last, 0, limit);
  if (length > 0 && last <= first) {
    // Enlarging the input (scale > 1) can round a 1-px span to nothing; keep one pixel.
    if (first < limit) {
      last = first + 1;
    } else {
      first = std::max(0, limit - 1);
      last = limit;
    }
  }
  *out_begin = first;
  *out_length = std::max(0, last - first);
}

}  // namespace

cv::Rect InputFromWorkingBox(const cv::Rect& box_in_working, double scale_x, double scale_y,
                             cv::Size input_size) {
  ATTEND_CHECK(scale_x > 0.0 && scale_y > 0.0) << "scales must be positive";
  cv::Rect box;
  InputFromWorkingSpan(box_in_working.x, box_in_working.width, scale_x, input_size.width, &box.x,
                       &box.width);
  InputFromWorkingSpan(box_in_working.y, box_in_working.height, scale_y, input_size.height, &box.y,
                       &box.height);
  return box;
}

FrameRecord InputFromWorking(const FrameRecord& record_in_working, double scale_x, double scale_y,
                             cv::Size input_size) {
  FrameRecord record = record_in_working;
  const double area_scale = scale_x * scale_y;
  for (TargetRecord& target : record.targets) {
    target.bbox = InputFromWorkingBox(target.bbox, scale_x, scale_y, input_size);
    if (target.area > 0) {
      target.area = std::max(1, static_cast<int>(std::lround(target.area / area_scale)));
    }
  }
  return record;
}

int VisibleTargets(const FrameRecord& record) {
  int n = 0;
  for (const TargetRecord& t : record.targets) n += Visible(t.state);
  return n;
}

std::string FrameRecordToJson(const FrameRecord& record) {
  nlohmann::ordered_json targets = nlohmann::ordered_json::array();
  for (const TargetRecord& t : record.targets) {
    nlohmann::ordered_json target = {{"id", t.id},
                                     {"bbox", {t.bbox.x, t.bbox.y, t.bbox.width, t.bbox.height}},
                                     {"area", t.area},
                                     {"saliency", t.saliency},
                                     {"state", TargetStateName(t.state)},
                                     {"kind", t.kind},
                                     {"similarity", t.similarity},
                                     {"tracker", t.tracker}};
    if (t.reason != ReleaseReason::kNone) target["reason"] = ReleaseReasonName(t.reason);
    targets.push_back(target);
  }
  nlohmann::ordered_json timings = nlohmann::ordered_json::object();
  for (const auto& [stage, ms] : record.timings.stages()) timings[stage] = ms;
  nlohmann::ordered_json line = {
      {"frame", record.frame}, {"targets", targets}, {"new", record.new_ids}};
  if (record.inhibited_fraction >= 0.0) line["inhibited_fraction"] = record.inhibited_fraction;
  line["timings_ms"] = timings;
  return JsonText(line);
}

}  // namespace attend
