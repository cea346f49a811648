#include "pipeline/frame_record.h"

#include <nlohmann/json.hpp>

namespace attend {

std::string FrameRecordToJson(const FrameRecord& record) {
  nlohmann::ordered_json targets = nlohmann::ordered_json::array();
  for (const TargetRecord& t : record.targets) {
    nlohmann::ordered_json target = {{"id", t.id},
                                     {"bbox", {t.bbox.x, t.bbox.y, t.bbox.width, t.bbox.height}},
                                     {"area", t.area},
                                     {"saliency", t.saliency},
                                     {"state", t.state},
                                     {"kind", t.kind},
                                     {"similarity", t.similarity},
                                     {"tracker", t.tracker}};
    if (!t.reason.empty()) target["reason"] = t.reason;
    targets.push_back(target);
  }
  nlohmann::ordered_json timings = nlohmann::ordered_json::object();
  for (const auto& [stage, ms] : record.timings.stages()) timings[stage] = ms;
  const nlohmann::ordered_json line = {{"frame", record.frame},
                                       {"targets", targets},
                                       {"new", record.new_ids},
                                       {"timings_ms", timings}};
  return line.dump();
}

}  // namespace attend
