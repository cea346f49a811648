// Eye-fixation datasets for scoring saliency maps against human fixations (NUS, MIT1003 and
// the like, converted to one layout):
//   DIR/stimuli/<id>.<ext>    the image shown (jpg, jpeg, png, ppm, pgm or bmp)
//   DIR/fixations/<id>.txt    its fixations, one a line: "subject x y [further columns]"
// Lines starting with '#' are comments and blank lines are skipped. x (column) and y (row) are
// 1-based pixels of the stimulus, as MATLAB-era datasets store them. Each subject's lines are
// in that subject's viewing order (the lines of different subjects may interleave).
//
// Durations (for scanpaths, eval/scanpath_metrics.h) come from one further column, found by
// DurationColumn: given by number, or named in the header, the comment lines before the first
// data line: the words after '#' are the columns' names, and the column named `duration_ms`
// (milliseconds) or `duration_s` (seconds) holds the durations, e.g.
//   # subject x y duration_ms            (crowd200: the 4th column, ms)
//   # subject x y onset_s duration_s     (NUS Scene500: the 5th column, s)
#pragma once

#include <string>
#include <vector>

namespace attend {

struct Fixation {
  int subject = 0;
  // 0-based pixel coordinates (the file's 1-based values minus 1); the fixation is at pixel
  // (round(x), round(y)). The reader keeps fixations that fall outside the image: the metrics
  // (eval/fixation_metrics.h) drop them, since only they know the map's size.
  double x = 0.0;
  double y = 0.0;
  // Seconds; negative when the file gives no durations.
  double duration_s = -1.0;
};

// Where ReadFixationFile finds durations.
struct DurationColumn {
  enum class Source {
    kNone,    // no durations: every duration_s stays -1
    kHeader,  // the column the header names duration_ms or duration_s; none without one
    kColumn,  // `column` in `seconds_per_unit`
  };
  Source source = Source::kNone;
  int column = 3;                  // 0-based (3: the fourth, after subject x y); kColumn only
  double seconds_per_unit = 1e-3;  // kColumn only
};

// Reads one fixation file. Throws InputError naming "<path>:<line>: <what is wrong>" for a bad
// line (too few columns, not a number, a negative or non-integer subject, a non-finite
// coordinate, a missing or negative duration where durations are read) and naming the path when
// the file cannot be read. An empty file gives no fixations.
std::vector<Fixation> ReadFixationFile(const std::string& path,
                                       const DurationColumn& durations = {});

// One subject's fixations in viewing order.
struct SubjectFixations {
  int subject = 0;
  std::vector<Fixation> fixations;
};

// `fixations` grouped by subject (subjects ascending), each in the order of `fixations`.
std::vector<SubjectFixations> GroupBySubject(const std::vector<Fixation>& fixations);

struct FixationItem {
  std::string id;              // the file stem shared by the stimulus and its fixation file
  std::string stimulus_path;   // DIR/stimuli/<id>.<ext>
  std::string fixations_path;  // DIR/fixations/<id>.txt
};

struct FixationDataset {
  std::string dir;
  std::vector<FixationItem> items;  // sorted by id
  int skipped = 0;  // stimuli without a fixation file plus fixation files without a stimulus
};

// Lists the items of DIR that have both a stimulus and a fixation file (files of other
// extensions are not part of the dataset and are ignored). Throws InputError naming what is
// missing: "DIR: no stimuli/ folder", "DIR: no fixations/ folder", "DIR: no stimulus has a
// fixation file", or two stimuli with the same id. Does not read the files.
FixationDataset OpenFixationDataset(const std::string& dir);

}  // namespace attend
