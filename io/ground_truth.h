// Ground truth of a sequence (SPEC 3.1): gt/objects.csv and gt/disparity/NNNNNN.pfm.
#pragma once

#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

namespace attend {

// One row of gt/objects.csv: an object's visible box in the left view of one frame.
struct GtObject {
  int frame = 0;
  int id = 0;
  cv::Rect2d box;                 // visible part, pixels of the left image; empty when hidden
  double visible_fraction = 0.0;  // visible pixels / pixels of the whole projected object
  // Pixels at the object's depth; empty when unknown (an empty field in objects.csv, SPEC 3.1).
  std::optional<double> disparity;
  std::string kind = "object";    // IsGroundTruthKind: "object", "skin", "car", ...; a KITTI label's type ("Car", ...)
};

// The header line of gt/objects.csv.
inline constexpr const char* kObjectsCsvHeader = "frame,id,x,y,w,h,visible_fraction,disparity,kind";

// The kinds an objects.csv row may have: "object" and "skin", and "car", "person" and "cyclist"
// of street scenes (docs/SYNTH.md).
bool IsGroundTruthKind(const std::string& kind);

// Reads gt/objects.csv. Lines may end in LF or CRLF; an empty disparity field is an unknown
// disparity. Throws InputError naming the file and line of a malformed row.
std::vector<GtObject> ReadObjectsCsv(const std::string& path);

// Writes gt/objects.csv with full float precision (round-trips exactly through ReadObjectsCsv);
// an unknown disparity is written as an empty field.
void WriteObjectsCsv(const std::string& path, const std::vector<GtObject>& objects);

// "gt/disparity/000042.pfm" below a sequence folder.
std::string GtDisparityPath(const std::string& sequence_folder, int frame);

// The file name of frame `index` in the SPEC 3.1 layout: "000042".
std::string FrameStem(int index);

}  // namespace attend
