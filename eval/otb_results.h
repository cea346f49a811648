// The results of an OTB one-pass evaluation of several trackers over several sequences
// (`attend eval-tracking --otb`, app/evaluate_otb.h; docs/TRACKING.md, "The OTB evaluation"),
// and what the report makes of them: the mean curves of all sequences and of each attribute,
// the summary per tracker, results.json and the summary table printed. eval/otb_report.h draws
// the page.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "eval/tracking_scores.h"

namespace attend {

// One tracker on one sequence.
struct OtbRun {
  bool started = false;       // false: the tracker could not start on frame 0's box (scores 0)
  TrackingScores scores;      // success curve, precision curve, AUC, precision@20, mean IoU
  double ms_per_frame = 0.0;  // mean time of one Track() call, over the calls made
  int updates = 0;            // Track() calls: frames after the first until the target is lost
  int not_found = 0;    // frames in which it reported the target not found (its last box kept)
  int lost_frames = 0;  // frames from the one it was lost in to the end (its last box kept)
  std::string tracks;   // its tracks.csv, relative to the report folder
};

struct OtbSequenceResult {
  std::string name;
  std::string folder;
  std::string ground_truth;
  int frames = 0;                       // frames scored
  int width = 0, height = 0;            // of the frames
  std::vector<std::string> attributes;  // OTB codes
  std::vector<OtbRun> runs;             // one per tracker, in OtbResults::trackers' order
};

struct OtbTracker {
  std::string name;                // attend, kcf, csrt
  std::string description;         // the kind and its settings: "bip, mode bounded, occlusion on"
  nlohmann::ordered_json options;  // the options it ran with, as the configuration spells them
};

struct OtbResults {
  std::vector<OtbTracker> trackers;
  std::vector<OtbSequenceResult> sequences;
  std::vector<std::string> notes;  // how the data were read, trackers that could not start
  // How and where it ran, for the record.
  std::string dir;
  std::string command_line;
  std::string date;  // UTC
  std::string cpu;
  std::string opencv;
  int opencv_threads = 1;
  double seconds = 0.0;  // wall time of the whole evaluation: reading, tracking, scoring
};

// The mean curves of a set of sequences: the OTB toolkit's plot of all sequences, or of the
// sequences that have one attribute.
struct OtbGroup {
  std::string code;   // "" for all sequences, else the attribute's code
  std::string title;  // "All sequences", "Scale Variation"
  std::vector<std::string> sequences;
  // Per tracker (OtbResults::trackers' order) the mean over the group's sequences of the
  // success curve (21 thresholds) and of the precision curve (0..50 px); the AUC is the mean of
  // the mean success curve (the mean of the sequences' AUCs), precision_20 the mean precision
  // curve at 20 px. The OTB toolkit's legends give these numbers.
  std::vector<std::vector<double>> success;
  std::vector<std::vector<double>> precision;
  std::vector<double> auc;
  std::vector<double> precision_20;
};

// All sequences first, then one group per attribute that some sequence has, in the
// benchmark's order of attributes (OtbAttributeBefore).
std::vector<OtbGroup> OtbGroups(const OtbResults& results);

// One tracker over every sequence.
struct OtbTrackerSummary {
  std::string name;
  std::string description;
  double auc = 0.0;           // the mean AUC over the sequences (the "All sequences" legend)
  double precision_20 = 0.0;  // the mean precision at 20 px
  double ms_per_frame = 0.0;  // the median over the sequences of its ms per frame
  // The median over the sequences of csrt's ms per frame divided by this tracker's: how many
  // times faster than csrt (1 for csrt); NaN when csrt is not among the trackers.
  double speed_vs_csrt = 0.0;
  int frames = 0;
  int not_found = 0;    // summed over the sequences
  int lost_frames = 0;  // summed over the sequences
  int not_started = 0;  // sequences it could not start on
};
std::vector<OtbTrackerSummary> SummariseOtb(const OtbResults& results);

// Every number of the page: the record (command, date, CPU), the trackers and their options,
// per sequence every tracker's scores and curves, the groups' mean curves, the summary and the
// notes. Non-finite numbers are null.
nlohmann::ordered_json OtbResultsJson(const OtbResults& results);

// The summary as a fixed-width text table, one tracker a line, for the terminal.
std::string OtbSummaryText(const OtbResults& results);

}  // namespace attend
