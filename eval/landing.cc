#include "eval/landing.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "io/target_state.h"
#include "util/median.h"

namespace attend {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();


// The box of half the width and height about the same centre.
cv::Rect2d InnerHalf(const cv::Rect2d& box) {
  return {box.x + 0.25 * box.width, box.y + 0.25 * box.height, 0.5 * box.width,
          0.5 * box.height};
}

bool Inside(const cv::Rect2d& box, double u, double v) {
  return u >= box.x && u < box.x + box.width && v >= box.y && v < box.y + box.height;
}

// The truth points inside the inner half of `box`.
std::vector<const TruthPoint*> PointsIn(const cv::Rect2d& box, const FrameTruth& truth) {
  const cv::Rect2d inner = InnerHalf(box);
  std::vector<const TruthPoint*> points;
  for (const TruthPoint& p : truth.points) {
    if (Inside(inner, p.u, p.v)) points.push_back(&p);
  }
  return points;
}

// The labelled object the box is on (the on_object rule), or null.
const TruthObject* ObjectUnder(const cv::Rect2d& box, const FrameTruth& truth,
                               const LandingOptions& options) {
  const double area = box.area();
  if (area <= 0.0) return nullptr;
  const TruthObject* best = nullptr;
  double best_cover = -1.0;
  for (const TruthObject& object : truth.objects) {
    const double inter = (box & object.box).area();
    const double cover = inter / area;
    const double iou = inter / (area + object.box.area() - inter);
    if ((cover >= options.object_cover || iou >= options.object_iou) && cover > best_cover) {
      best = &object;
      best_cover = cover;
    }
  }
  return best;
}

// What is learnt of one target-frame.
struct Landing {
  const TruthObject* object = nullptr;
  bool sky = false, ground = false, no_depth = false;
  std::optional<double> truth_depth_m;  // the median of the inner half's points, when enough
};

Landing Classify(const cv::Rect2d& box, const FrameTruth& truth, const LandingOptions& options) {
  Landing landing;
  landing.object = ObjectUnder(box, truth, options);
  const std::vector<const TruthPoint*> points = PointsIn(box, truth);
  landing.no_depth = points.empty();
  const double cu = box.x + 0.5 * box.width;
  const double cv_ = box.y + 0.5 * box.height;
  landing.sky = points.empty() && (!truth.horizon.valid() || cv_ < truth.horizon.HorizonV(cu));
  if (!points.empty()) {
    const auto ground = std::count_if(points.begin(), points.end(),
                                      [](const TruthPoint* p) { return p->ground; });
    landing.ground = ground >= options.ground_share * static_cast<double>(points.size());
  }
  if (static_cast<int>(points.size()) >= options.depth_points) {
    std::vector<double> depths;
    for (const TruthPoint* p : points) depths.push_back(p->depth_m);
    landing.truth_depth_m = MedianOf(depths);
  }
  return landing;
}

// The labelled objects of the scored frames, by id, with their first visible frame.
std::map<int, LandingObject> ObjectsInView(const std::vector<FrameRecord>& frames,
                                           const SceneTruth& truth) {
  std::map<int, LandingObject> objects;
  for (const FrameRecord& record : frames) {
    const auto it = truth.find(record.frame);
    if (it == truth.end()) continue;
    for (const TruthObject& object : it->second.objects) {
      const auto [entry, inserted] = objects.try_emplace(object.id);
      if (inserted || record.frame < entry->second.first_visible) {
        entry->second.id = object.id;
        entry->second.kind = object.kind;
        entry->second.first_visible = record.frame;
      }
    }
  }
  return objects;
}

}  // namespace

double LandingScores::Share(int count) const {
  return target_frames > 0 ? static_cast<double>(count) / target_frames : kNaN;
}

double LandingScores::ObjectShareInView() const {
  return target_frames_with_objects > 0
             ? static_cast<double>(on_object_with_objects) / target_frames_with_objects
             : kNaN;
}

LandingScores EvaluateLanding(const std::vector<FrameRecord>& frames, const SceneTruth& truth,
                              const LandingOptions& options) {
  LandingScores scores;
  scores.options = options;
  std::map<int, LandingObject> objects = ObjectsInView(frames, truth);
  std::vector<double> relative_errors, abs_errors;
  for (const FrameRecord& record : frames) {
    const auto it = truth.find(record.frame);
    if (it == truth.end()) {
      ++scores.frames_without_truth;
      continue;
    }
    const FrameTruth& frame = it->second;
    ++scores.frames;
    const bool objects_in_view = !frame.objects.empty();
    scores.frames_with_objects += objects_in_view ? 1 : 0;
    for (const TargetRecord& target : record.targets) {
      if (!Visible(target.state)) continue;
      const Landing landing = Classify(cv::Rect2d(target.bbox), frame, options);
      ++scores.target_frames;
      scores.on_object += landing.object != nullptr ? 1 : 0;
      scores.on_sky += landing.sky ? 1 : 0;
      scores.on_ground += landing.ground ? 1 : 0;
      scores.without_depth += landing.no_depth ? 1 : 0;
      scores.elsewhere += landing.object == nullptr && !landing.sky && !landing.ground ? 1 : 0;
      if (objects_in_view) {
        ++scores.target_frames_with_objects;
        scores.on_object_with_objects += landing.object != nullptr ? 1 : 0;
      }
      if (landing.object != nullptr) {
        LandingObject& object = objects[landing.object->id];
        if (!object.first_attended || record.frame < *object.first_attended) {
          object.first_attended = record.frame;
        }
      }
      if (target.has_position && landing.truth_depth_m.has_value()) {
        const double error = std::abs(target.position_m[2] - *landing.truth_depth_m);
        abs_errors.push_back(error);
        relative_errors.push_back(error / *landing.truth_depth_m);
      }
    }
  }
  for (auto& [id, object] : objects) {
    if (object.first_attended) {
      object.frames_to_attend = *object.first_attended - object.first_visible;
      if (*object.frames_to_attend <= options.attended_window) ++scores.attended_within;
    }
    scores.objects.push_back(object);
  }
  scores.depth_target_frames = static_cast<int>(relative_errors.size());
  if (!relative_errors.empty()) {
    const auto within = std::count_if(relative_errors.begin(), relative_errors.end(),
                                      [&](double e) { return e <= options.depth_within; });
    scores.depth_share_within = static_cast<double>(within) / relative_errors.size();
  }
  scores.median_relative_depth_error = MedianOf(relative_errors);
  scores.median_abs_depth_error_m = MedianOf(abs_errors);
  return scores;
}

nlohmann::ordered_json LandingToJson(const LandingScores& s) {
  auto number = [](double v) {
    return std::isfinite(v) ? nlohmann::ordered_json(v) : nlohmann::ordered_json();
  };
  auto optional = [](const std::optional<int>& v) {
    return v ? nlohmann::ordered_json(*v) : nlohmann::ordered_json();
  };
  nlohmann::ordered_json per_object = nlohmann::ordered_json::array();
  for (const LandingObject& o : s.objects) {
    per_object.push_back({{"id", o.id},
                          {"kind", o.kind},
                          {"first_visible", o.first_visible},
                          {"first_attended", optional(o.first_attended)},
                          {"frames_to_attend", optional(o.frames_to_attend)}});
  }
  return {{"frames", s.frames},
          {"frames_without_truth", s.frames_without_truth},
          {"target_frames", s.target_frames},
          {"on_object", s.on_object},
          {"on_sky", s.on_sky},
          {"on_ground", s.on_ground},
          {"without_depth", s.without_depth},
          {"elsewhere", s.elsewhere},
          {"on_object_share", number(s.Share(s.on_object))},
          {"on_sky_share", number(s.Share(s.on_sky))},
          {"on_ground_share", number(s.Share(s.on_ground))},
          {"without_depth_share", number(s.Share(s.without_depth))},
          {"elsewhere_share", number(s.Share(s.elsewhere))},
          {"frames_with_objects", s.frames_with_objects},
          {"target_frames_with_objects", s.target_frames_with_objects},
          {"object_share_in_view", number(s.ObjectShareInView())},
          {"objects", static_cast<int>(s.objects.size())},
          {"attended_window", s.options.attended_window},
          {"attended_within", s.attended_within},
          {"per_object", per_object},
          {"depth",
           {{"target_frames", s.depth_target_frames},
            {"share_within_10_percent", number(s.depth_share_within)},
            {"median_relative_error", number(s.median_relative_depth_error)},
            {"median_abs_error_m", number(s.median_abs_depth_error_m)}}}};
}

}  // namespace attend
