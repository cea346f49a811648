// Scanpath similarity: how alike two sequences of fixations are in where they go and in what
// order. The three measures the eye-movement field uses (docs/FIXATIONS.md, "Scanpaths"):
//
//  - ScanMatch (Cristino, Mathôt, Theeuwes & Gilchrist, "ScanMatch: a novel method for
//    comparing fixation sequences", Behavior Research Methods 42(3), 2010): fixations coded
//    by the cell of a grid they fall in, optionally repeated once per temporal bin of their
//    duration, aligned by Needleman-Wunsch with a substitution matrix from the distance
//    between cells;
//  - the sequence score: the string edit (Levenshtein) distance between the grid codes;
//  - MultiMatch (Jarodzka, Holmqvist & Nyström, ETRA 2010; Dewhurst et al., "It depends on how
//    you look at it", Behavior Research Methods 44(4), 2012): the scanpaths as saccade vectors,
//    aligned by the cheapest path through the matrix of vector differences, compared on shape,
//    direction, length, position and duration.
//
// Every similarity is in [0, 1], 1 for identical scanpaths. A scanpath is a sequence of
// Fixation (eval/fixation_data.h: 0-based pixels of the image, duration in seconds; `subject`
// is not used). Scanpaths of different lengths are compared as they are: the alignments pair
// them. Bad parameters or an empty scanpath are caller bugs (ATTEND_CHECK): the caller checks
// its input and names the file.
#pragma once

#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "eval/fixation_data.h"

namespace attend {

using Scanpath = std::vector<Fixation>;

// The grid that codes fixations, `columns` x `rows` cells of equal size over the image. 12 x 8
// is the ScanMatch toolbox's default.
struct ScanpathGrid {
  int columns = 12;
  int rows = 8;
};

// Each fixation's cell, column + columns x row (row-major); a fixation outside the image takes
// the nearest cell.
std::vector<int> GridCodes(const Scanpath& path, cv::Size image, const ScanpathGrid& grid);

// The amplitude of each saccade of `path` in cells (dx / cell width, dy / cell height): what
// ScanMatchThreshold takes.
std::vector<double> SaccadeAmplitudesInCells(const Scanpath& path, cv::Size image,
                                             const ScanpathGrid& grid);

// Cristino et al. (2010): the substitution matrix's threshold is two standard deviations of the
// saccade amplitudes (population sd), in cells. `amplitudes` must not be empty.
double ScanMatchThreshold(const std::vector<double>& amplitudes);

struct ScanMatchOptions {
  ScanpathGrid grid;
  // Cells: the distance between two cells' centres at which substituting one for the other
  // scores 0. Must be > 0; the caller takes ScanMatchThreshold of its data, or the toolbox's
  // fixed 3.5.
  double threshold = 3.5;
  // Score of a gap in the alignment (<= 0). The paper's and the toolbox's: 0.
  double gap = 0.0;
  // Seconds: each fixation is repeated round(duration / temporal_bin_s) times (at least once),
  // so that the alignment weighs time. 0: every fixation once (the toolbox's default). Needs
  // durations (>= 0) in both scanpaths.
  double temporal_bin_s = 0.0;

  bool Check(std::string* error) const;
};

// The substitution score of cells `a` and `b`: threshold - distance between their centres in
// cells. Cristino et al. take max distance - distance, shifted down by (max distance -
// threshold) so that cells further apart than the threshold score below 0: the same thing.
double ScanMatchSubstitution(int a, int b, const ScanMatchOptions& options);

// The sequence of letters ScanMatch aligns: GridCodes, each repeated per temporal bin.
std::vector<int> ScanMatchSequence(const Scanpath& path, cv::Size image,
                                   const ScanMatchOptions& options);

// The Needleman-Wunsch global alignment score of `a` and `b`: the highest sum of
// substitution(a_i, b_j) over aligned pairs plus `gap` per letter aligned with nothing.
double NeedlemanWunschScore(const std::vector<int>& a, const std::vector<int>& b,
                            const ScanMatchOptions& options);

// ScanMatch similarity: the alignment score over its maximum, threshold x the longer
// sequence's length (the toolbox's normalisation): 1 for identical scanpaths, 0 when no pair
// of cells lies within the threshold. With gap 0 it is never negative.
double ScanMatch(const Scanpath& a, const Scanpath& b, cv::Size image,
                 const ScanMatchOptions& options);

// The Levenshtein distance between two code sequences: the fewest insertions, deletions and
// substitutions that turn one into the other.
int CodeEditDistance(const std::vector<int>& a, const std::vector<int>& b);

// The sequence score: 1 - CodeEditDistance(GridCodes(a), GridCodes(b)) / the longer length.
double SequenceScore(const Scanpath& a, const Scanpath& b, cv::Size image,
                     const ScanpathGrid& grid);

// A saccade of MultiMatch's vector representation: from fixation (x, y) by (dx, dy), that
// fixation lasting duration_s.
struct Saccade {
  double x = 0.0;
  double y = 0.0;
  double dx = 0.0;
  double dy = 0.0;
  double duration_s = 0.0;
};

// Scanpath simplification (Jarodzka et al. 2010, sec. 3.1; Dewhurst et al. 2012): off by
// default, as in the Python reimplementation multimatch-gaze; the thresholds are those the
// MultiMatch toolbox uses when it simplifies.
struct MultiMatchOptions {
  bool simplify = false;
  double amplitude_threshold = 0.1;  // share of the image diagonal
  double direction_threshold_deg = 45.0;
  double duration_threshold_s = 0.3;

  bool Check(std::string* error) const;
};

// The saccades of `path` (one fewer than its fixations), each starting at a fixation with that
// fixation's duration.
std::vector<Saccade> SaccadeVectors(const Scanpath& path);

// Merges consecutive saccades until none is merged: two saccades whose directions differ by
// less than the direction threshold, or which are both shorter than the amplitude threshold
// (x the image diagonal), become one (their vectors summed, from the first one's start) when
// the fixation between them is shorter than the duration threshold.
std::vector<Saccade> SimplifySaccades(std::vector<Saccade> saccades, cv::Size image,
                                      const MultiMatchOptions& options);

// The alignment: pairs (i, j) of saccades of `a` and `b` on the path from (0, 0) to (n-1, m-1)
// through the matrix of vector differences |(dx, dy)_i - (dx, dy)_j|, moving right, down or
// diagonally, with the smallest sum of differences (Jarodzka et al. 2010, sec. 3.2). Both must
// hold a saccade.
std::vector<std::pair<int, int>> AlignSaccades(const std::vector<Saccade>& a,
                                               const std::vector<Saccade>& b);

// The five similarities, each 1 - the median over the aligned pairs of a difference over its
// largest possible value (Dewhurst et al. 2012, as multimatch-gaze normalises them):
struct MultiMatchScores {
  double shape = 0.0;      // vector difference |u - v| over 2 x the image diagonal
  double direction = 0.0;  // angle between the saccades over pi
  double length = 0.0;     // amplitude difference over the diagonal
  double position = 0.0;   // distance between the saccades' start fixations over the diagonal
  // |d_u - d_v| / max(d_u, d_v) of the start fixations (0 when both are 0); NaN when a
  // duration is unknown (negative).
  double duration = 0.0;
};

// nullopt when either scanpath has fewer than two fixations (no saccade to compare).
std::optional<MultiMatchScores> MultiMatch(const Scanpath& a, const Scanpath& b, cv::Size image,
                                           const MultiMatchOptions& options);

}  // namespace attend
