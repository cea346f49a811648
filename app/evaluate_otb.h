// The controller of `attend eval-tracking --otb DIR --out REPORT` (docs/TRACKING.md, "The OTB
// evaluation"): the one-pass evaluation (OPE) of the OTB benchmark over the sequences of a
// folder, for several trackers in the same run. Every tracker starts on frame 0 from the true
// box and runs to the end; the trackers take turns frame by frame on one OpenCV thread, each
// frame read once and handed to all of them, and only their Track() calls are timed. Writes
// REPORT/tracks/<tracker>/<sequence>.csv (tracks.csv), REPORT/index.html (eval/otb_report.h) and,
// last, REPORT/results.json (eval/otb_results.h). The command only parses and prints.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "eval/otb_results.h"
#include "eval/otb_sequences.h"
#include "tracker/target_tracker.h"

namespace attend {

// The trackers the evaluation knows, in the default order: attend (the tracker `attend track`
// builds), kcf and csrt (OpenCV's, configured as bench/tracking_bench.cc does).
const std::vector<std::string>& OtbTrackerNames();

struct OtbEvaluationRequest {
  std::string dir;  // a folder of OTB sequences, or one sequence
  std::string out;  // the report folder
  std::vector<std::string> trackers = OtbTrackerNames();
  // Sequences to evaluate, by name ("Jogging-1") or folder name ("Jogging": all of its
  // ground-truth files); empty: every sequence found.
  std::vector<std::string> sequences;
  TargetTrackerOptions attend;  // the options of the tracker called attend
  bool overwrite = false;       // replace a previous report in `out`
  std::string command_line;     // recorded in the report
};

// Hears the evaluation's progress.
struct OtbObserver {
  // Before sequence `index` (from 0) of `count` is tracked.
  std::function<void(const OtbSequence& sequence, int index, int count)> on_sequence;
  // After it was tracked and scored (runs in `trackers`' order).
  std::function<void(const OtbSequenceResult& result, const std::vector<OtbTracker>& trackers)>
      on_result;
};

// The options of the tracker called `name` (one of OtbTrackerNames()): `attend` itself for
// "attend"; for kcf and csrt OpenCV's default parameters, KCF's detect_thresh 0 (a weak response
// is not a failure) and lost_frames at its maximum, so that a failing tracker keeps its last
// box to the end (the OTB rule) as in bench/tracking_bench.cc.
TargetTrackerOptions OtbTrackerOptions(const std::string& name, const TargetTrackerOptions& attend);

// Runs the evaluation and writes the report; returns what it wrote. Everything is checked before
// the report folder is touched: ConfigError for an unknown or repeated tracker, or a sequence
// not found; InputError for DIR (FindOtbSequences); OutputError for REPORT not empty without
// `overwrite` (or not holding a previous report). An image that cannot be read is an
// InputError naming the sequence, frame and file; REPORT then holds the tracks of the sequences
// done but no results.json, which is written last, so a report without it is not complete.
OtbResults EvaluateOtb(const OtbEvaluationRequest& request, const OtbObserver& observer = {});

}  // namespace attend
