// Eye-fixation datasets for scoring saliency maps against human fixations (NUS, MIT1003 and
// the like, converted to one layout):
//   DIR/stimuli/<id>.<ext>    the image shown (jpg, jpeg, png, ppm, pgm or bmp)
//   DIR/fixations/<id>.txt    its fixations, one a line: "subject x y [further columns]"
// Lines starting with '#' are comments and blank lines are skipped. x (column) and y (row) are
// 1-based pixels of the stimulus, as MATLAB-era datasets store them.
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
};

// Reads one fixation file. Throws InputError naming "<path>:<line>: <what is wrong>" for a bad
// line (too few columns, not a number, a negative or non-integer subject, a non-finite
// coordinate) and naming the path when the file cannot be read. An empty file gives no fixations.
std::vector<Fixation> ReadFixationFile(const std::string& path);

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
