// Tracking results and ground truth as files (SPEC 3.2): tracks.csv, written by `attend track`
// and read by `attend eval-tracking`, and OTB's groundtruth_rect.txt. docs/TRACKING.md has the
// formats with worked examples; eval/tracking_scores.h scores the boxes.
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace attend {

// One row of tracks.csv: frame,id,x,y,w,h,state.
struct TrackRow {
  int frame = 0;
  int id = 0;
  cv::Rect2d box;
  std::string state;  // found, occluded or lost
};

// tracks.csv: the header line "frame,id,x,y,w,h,state", then one row a target and frame; x, y,
// w, h in 0-based pixels of the frame (x, y the top-left corner), state found, occluded or lost.
// Blank lines are ignored. A missing header, a row without 7 fields, a field that is not a
// number, a non-integer frame or id, a negative frame, id, w or h, or another state: InputError
// naming the file and line.
std::vector<TrackRow> ReadTracksCsv(const std::string& path);
// Writes tracks.csv with its header, numbers in full precision (round trip through
// ReadTracksCsv is exact). OutputError when it cannot.
void WriteTracksCsv(const std::string& path, const std::vector<TrackRow>& rows);

// An OTB groundtruth_rect.txt: one box a line, "x y w h" separated by any run of tabs, spaces
// and commas, 1-based pixel coordinates (converted here to 0-based: x - 1, y - 1). Frame i of the
// file is line i + 1. A box with w or h 0, or with a NaN field, is "no ground truth" and comes
// back empty (Rect2d()). Trailing blank lines are ignored; a blank line before the last box, a
// line without 4 numbers or a negative w or h is InputError naming the file and line.
std::vector<cv::Rect2d> ReadOtbGroundTruth(const std::string& path);

}  // namespace attend
