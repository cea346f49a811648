#include "eval/otb_results.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <set>

#include "eval/otb_sequences.h"
#include "util/strings.h"
#include "util/median.h"

namespace attend {

namespace {

using Json = nlohmann::ordered_json;

// A number, or null when it is not finite (JSON has no NaN).
Json JsonNumber(double value) { return std::isfinite(value) ? Json(value) : Json(); }

Json JsonNumbers(const std::vector<double>& values) {
  Json array = Json::array();
  for (const double value : values) array.push_back(JsonNumber(value));
  return array;
}


// The mean of the curves of `runs` (curves of another length count as zeros).
std::vector<double> MeanCurve(const std::vector<const std::vector<double>*>& curves, size_t size) {
  std::vector<double> mean(size, 0.0);
  if (curves.empty()) return mean;
  for (const std::vector<double>* curve : curves) {
    if (curve->size() != size) continue;
    for (size_t i = 0; i < size; ++i) mean[i] += (*curve)[i];
  }
  for (double& value : mean) value /= static_cast<double>(curves.size());
  return mean;
}

double Mean(const std::vector<double>& values) {
  if (values.empty()) return 0.0;
  double sum = 0.0;
  for (const double value : values) sum += value;
  return sum / static_cast<double>(values.size());
}

OtbGroup MakeGroup(const OtbResults& results, const std::string& code, const std::string& title,
                   const std::vector<size_t>& members) {
  OtbGroup group;
  group.code = code;
  group.title = title;
  for (const size_t s : members) group.sequences.push_back(results.sequences[s].name);
  const size_t success_size = SuccessThresholds().size();
  const size_t precision_size = PrecisionThresholds().size();
  for (size_t t = 0; t < results.trackers.size(); ++t) {
    std::vector<const std::vector<double>*> success, precision;
    for (const size_t s : members) {
      const OtbRun& run = results.sequences[s].runs[t];
      success.push_back(&run.scores.success);
      precision.push_back(&run.scores.precision);
    }
    group.success.push_back(MeanCurve(success, success_size));
    group.precision.push_back(MeanCurve(precision, precision_size));
    group.auc.push_back(Mean(group.success.back()));
    group.precision_20.push_back(group.precision.back()[20]);
  }
  return group;
}

int TrackerIndex(const OtbResults& results, const std::string& name) {
  for (size_t t = 0; t < results.trackers.size(); ++t) {
    if (results.trackers[t].name == name) return static_cast<int>(t);
  }
  return -1;
}

Json RunJson(const OtbRun& run) {
  return {{"started", run.started},
          {"success_auc", JsonNumber(run.scores.success_auc)},
          {"precision_20", JsonNumber(run.scores.precision_20)},
          {"mean_iou", JsonNumber(run.scores.mean_iou)},
          {"ms_per_frame", JsonNumber(run.ms_per_frame)},
          {"updates", run.updates},
          {"not_found", run.not_found},
          {"lost_frames", run.lost_frames},
          {"tracks", run.tracks},
          {"success", JsonNumbers(run.scores.success)},
          {"precision", JsonNumbers(run.scores.precision)}};
}

Json SequencesJson(const OtbResults& results) {
  Json sequences = Json::array();
  for (const OtbSequenceResult& sequence : results.sequences) {
    Json runs = Json::object();
    for (size_t t = 0; t < results.trackers.size(); ++t) {
      runs[results.trackers[t].name] = RunJson(sequence.runs[t]);
    }
    sequences.push_back({{"name", sequence.name},
                         {"folder", sequence.folder},
                         {"ground_truth", sequence.ground_truth},
                         {"frames", sequence.frames},
                         {"size", {sequence.width, sequence.height}},
                         {"attributes", sequence.attributes},
                         {"trackers", runs}});
  }
  return sequences;
}

Json GroupsJson(const OtbResults& results) {
  Json groups = Json::array();
  for (const OtbGroup& group : OtbGroups(results)) {
    Json trackers = Json::object();
    for (size_t t = 0; t < results.trackers.size(); ++t) {
      trackers[results.trackers[t].name] = {{"success_auc", JsonNumber(group.auc[t])},
                                            {"precision_20", JsonNumber(group.precision_20[t])},
                                            {"success", JsonNumbers(group.success[t])},
                                            {"precision", JsonNumbers(group.precision[t])}};
    }
    groups.push_back({{"attribute", group.code.empty() ? Json() : Json(group.code)},
                      {"title", group.title},
                      {"sequences", group.sequences},
                      {"trackers", trackers}});
  }
  return groups;
}

}  // namespace

std::vector<OtbGroup> OtbGroups(const OtbResults& results) {
  std::vector<size_t> all;
  std::set<std::string> codes;
  for (size_t s = 0; s < results.sequences.size(); ++s) {
    all.push_back(s);
    codes.insert(results.sequences[s].attributes.begin(), results.sequences[s].attributes.end());
  }
  std::vector<OtbGroup> groups = {MakeGroup(results, "", "All sequences", all)};
  std::vector<std::string> ordered(codes.begin(), codes.end());
  std::sort(ordered.begin(), ordered.end(), OtbAttributeBefore);
  for (const std::string& code : ordered) {
    std::vector<size_t> members;
    for (size_t s = 0; s < results.sequences.size(); ++s) {
      const std::vector<std::string>& attributes = results.sequences[s].attributes;
      if (std::find(attributes.begin(), attributes.end(), code) != attributes.end()) {
        members.push_back(s);
      }
    }
    groups.push_back(MakeGroup(results, code, OtbAttributeName(code), members));
  }
  return groups;
}

std::vector<OtbTrackerSummary> SummariseOtb(const OtbResults& results) {
  const int csrt = TrackerIndex(results, "csrt");
  std::vector<OtbTrackerSummary> summaries;
  for (size_t t = 0; t < results.trackers.size(); ++t) {
    OtbTrackerSummary summary;
    summary.name = results.trackers[t].name;
    summary.description = results.trackers[t].description;
    std::vector<double> aucs, precisions, ms, ratios;
    for (const OtbSequenceResult& sequence : results.sequences) {
      const OtbRun& run = sequence.runs[t];
      aucs.push_back(run.scores.success_auc);
      precisions.push_back(run.scores.precision_20);
      summary.frames += sequence.frames;
      summary.not_found += run.not_found;
      summary.lost_frames += run.lost_frames;
      summary.not_started += run.started ? 0 : 1;
      if (run.updates == 0) continue;
      ms.push_back(run.ms_per_frame);
      if (csrt < 0) continue;
      const OtbRun& reference = sequence.runs[csrt];
      if (reference.updates > 0 && run.ms_per_frame > 0.0) {
        ratios.push_back(reference.ms_per_frame / run.ms_per_frame);
      }
    }
    summary.auc = Mean(aucs);
    summary.precision_20 = Mean(precisions);
    summary.ms_per_frame = MedianOf(ms);
    summary.speed_vs_csrt = MedianOf(ratios);
    summaries.push_back(summary);
  }
  return summaries;
}

nlohmann::ordered_json OtbResultsJson(const OtbResults& results) {
  Json trackers = Json::array();
  for (const OtbTracker& tracker : results.trackers) {
    trackers.push_back({{"name", tracker.name},
                        {"description", tracker.description},
                        {"options", tracker.options}});
  }
  Json summary = Json::array();
  for (const OtbTrackerSummary& s : SummariseOtb(results)) {
    summary.push_back({{"tracker", s.name},
                       {"success_auc", JsonNumber(s.auc)},
                       {"precision_20", JsonNumber(s.precision_20)},
                       {"ms_per_frame_median", JsonNumber(s.ms_per_frame)},
                       {"speed_vs_csrt_median", JsonNumber(s.speed_vs_csrt)},
                       {"frames", s.frames},
                       {"not_found", s.not_found},
                       {"lost_frames", s.lost_frames},
                       {"not_started", s.not_started}});
  }
  return {{"command", results.command_line},
          {"date", results.date},
          {"cpu", results.cpu},
          {"opencv", results.opencv},
          {"opencv_threads", results.opencv_threads},
          {"seconds", JsonNumber(results.seconds)},
          {"dir", results.dir},
          {"evaluation", "OPE"},
          {"success_thresholds", JsonNumbers(SuccessThresholds())},
          {"precision_thresholds_px", JsonNumbers(PrecisionThresholds())},
          {"trackers", trackers},
          {"summary", summary},
          {"sequences", SequencesJson(results)},
          {"groups", GroupsJson(results)},
          {"notes", results.notes}};
}

std::string OtbSummaryText(const OtbResults& results) {
  int frames = 0;
  for (const OtbSequenceResult& sequence : results.sequences) frames += sequence.frames;
  std::string text = "OTB one-pass evaluation: " + std::to_string(results.sequences.size()) +
                     " sequences, " + std::to_string(frames) + " frames\n";
  char line[256];
  std::snprintf(line, sizeof(line), "%-10s %6s %6s %9s %7s %9s %6s  %s\n", "tracker", "AUC", "P@20",
                "ms/frame", "x csrt", "not found", "lost", "kind");
  text += line;
  for (const OtbTrackerSummary& s : SummariseOtb(results)) {
    const std::string ratio = std::isfinite(s.speed_vs_csrt) ? Fixed(s.speed_vs_csrt, 2) : "-";
    const std::string ms = std::isfinite(s.ms_per_frame) ? Fixed(s.ms_per_frame, 2) : "-";
    std::snprintf(line, sizeof(line), "%-10s %6.3f %6.3f %9s %7s %9d %6d  %s\n", s.name.c_str(),
                  s.auc, s.precision_20, ms.c_str(), ratio.c_str(), s.not_found, s.lost_frames,
                  s.description.c_str());
    text += line;
  }
  return text;
}

}  // namespace attend
