// Writes small sequences in the OTB benchmark's layout for tests (eval/otb_sequences.h): drawn
// frames whose true boxes are known by construction.
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace attend::testing {

// A textured square moving in a straight line: its top-left corner is start + i * step in frame
// i (rounded to whole pixels), its side `side`.
struct DrawnSquare {
  cv::Point2d start;
  cv::Point2d step;
  int side = 24;
};

// Writes folder/img/0001.jpg ... (`frames` frames of `size`: the squares, each a checkerboard of
// saturated colours of its own, over a blotchy textured background) and one ground-truth file
// per square, tab-separated and 1-based as OTB writes them: groundtruth_rect.txt for a single
// square unless `numbered`, else groundtruth_rect.1.txt, .2.txt, ... Returns each square's true
// boxes (0-based), frame by frame.
std::vector<std::vector<cv::Rect>> MakeOtbSequence(const std::string& folder, int frames,
                                                   const cv::Size& size,
                                                   const std::vector<DrawnSquare>& squares,
                                                   bool numbered = false);

}  // namespace attend::testing
