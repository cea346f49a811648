// Limits on what attend reads, each refused up front with a message that names the input
// (docs/LIMITS.md lists them with the reasons). They bound what an input can make attend
// allocate: a line of a CSV file may not make a scorer allocate a slot for each of 10^9 frames.
#pragma once

namespace attend {

// Frame numbers in gt/objects.csv, tracks.csv and frames.jsonl: 0..kMaxFrameNumber (at 30
// frames a second, over nine hours). Scorers allocate per frame number up to the largest.
inline constexpr int kMaxFrameNumber = 1000000;

// Coordinates and sizes of the integer boxes of frames.jsonl, in pixels: |x|, |y|, w, h at most
// this, so that areas and sums of coordinates stay far inside int. (The boxes of objects.csv
// and tracks.csv are real numbers, only required to be finite.)
inline constexpr int kMaxBoxCoordinate = 1 << 16;

// Target and object ids in those files: 0..kMaxId.
inline constexpr int kMaxId = 1 << 30;

// Targets in one record of frames.jsonl. A run keeps at most select.max_targets (at most 1000)
// targets; attend track-detections about as many as there are people in view. The scorers,
// reports and comparisons hold every target of a run: 10^6 targets in one record took 6 GB.
inline constexpr int kMaxTargetsPerRecord = 10000;

// Bytes in one line of frames.jsonl: kMaxTargetsPerRecord targets of about 400 bytes each.
inline constexpr long kMaxRecordBytes = 8L << 20;

}  // namespace attend
