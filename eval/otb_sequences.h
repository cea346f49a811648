// Sequences in the layout of the OTB benchmark (Wu, Lim and Yang, CVPR 2013 and TPAMI 2015), as
// its toolkit and its download ship them, for `attend eval-tracking --otb` (docs/TRACKING.md,
// "The OTB evaluation"):
//   SEQ/img/0001.jpg ...              the frames (any of io/frame_files.h's extensions)
//   SEQ/groundtruth_rect.txt          one box "x y w h" a line, 1-based (io/tracking_files.h)
//   SEQ/groundtruth_rect.N.txt        instead, one file per target (Jogging: .1 and .2)
//   SEQ/attrs.txt                     optional: the attribute codes, "SV, DEF, FM, OPR, BC"
//   SEQ/cfg.json                      optional: startFrame, endFrame, attributes
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace attend {

struct OtbSequence {
  // The folder's name, or with several ground-truth files "FOLDER-N" for groundtruth_rect.N.txt,
  // as the OTB toolkit names them (Jogging-1, Jogging-2).
  std::string name;
  std::string folder;
  std::string folder_name;   // the folder's own name ("Jogging" for Jogging-1)
  std::string ground_truth;  // the groundtruth_rect file read
  // Frame i of the evaluation: its image and its true box (0-based pixels; empty when the file
  // gives none). Both have the same length, the frames that have both an image and a line.
  std::vector<std::string> images;
  std::vector<cv::Rect2d> truth;
  // The attribute codes (upper case, in the file's order): attrs.txt where present, else
  // cfg.json's "attributes", else none.
  std::vector<std::string> attributes;
  int first_image = 0;  // the index in img/ of frame 0 (cfg.json's startFrame - 1)
  // How the counts were reconciled, when images and boxes differ in number.
  std::vector<std::string> notes;
};

// Whether `folder` is an OTB sequence: an img/ folder and at least one groundtruth_rect.txt or
// groundtruth_rect.N.txt beside it.
bool IsOtbSequenceFolder(const std::string& folder);

// The sequences of `dir`: `dir` itself when it is a sequence folder, else each of its
// sub-folders that is one (one level down), sorted by name. Reads every ground-truth file,
// attrs.txt and cfg.json and lists the images (without decoding them), so that bad input is
// found before any tracking. Frame 0 is the image of cfg.json's startFrame (the first image
// without one); the frames are those up to endFrame (the last image) that also have a line of
// ground truth: where images and lines differ in number, the shorter decides and a note says so.
// Sub-folders with img/ but no ground truth are skipped with a note in `notes` (may be null).
// InputError: `dir` missing or not a folder, no sequence in it, a ground-truth line that does
// not parse (file and line), no box on frame 0, an unreadable attrs.txt or cfg.json (file and
// key), a startFrame or endFrame outside the images, an img/ without images.
std::vector<OtbSequence> FindOtbSequences(const std::string& dir,
                                          std::vector<std::string>* notes = nullptr);

// The full name of an OTB attribute code ("SV" -> "Scale Variation"), the code itself when it
// is not one of the benchmark's eleven.
std::string OtbAttributeName(const std::string& code);
// The order in which the benchmark lists its attributes: IV, SV, OCC, DEF, MB, FM, IPR, OPR, OV,
// BC, LR; other codes after them, by name.
bool OtbAttributeBefore(const std::string& a, const std::string& b);

}  // namespace attend
