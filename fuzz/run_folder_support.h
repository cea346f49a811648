// The valid run folder and ground truth that the run-folder targets put their input into
// (docs/FUZZING.md): small, made in code with the project's own writers, so valid by
// construction. Three frames of 32x24 with two targets, one of them skin.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "io/ground_truth.h"
#include "io/frame_record.h"

namespace attend::fuzz {

inline constexpr int kRunWidth = 32;
inline constexpr int kRunHeight = 24;

// The frames as `attend run` records them in frames.jsonl.
std::vector<FrameRecord> ValidFrames();
// The ground truth of those frames (gt/objects.csv): the two objects, disparity known for one.
std::vector<GtObject> ValidObjects();

// The three files of a run folder that `attend eval` and `attend compare` read.
struct RunFiles {
  std::string frames_jsonl;
  std::string config_yaml;  // the effective configuration, sequence.folder set
  std::string summary_json;
};

// The files of a run of ValidFrames() on the sequence folder `sequence`.
RunFiles ValidRunFiles(const std::string& sequence);

// SEQ/gt/objects.csv (ValidObjects) and SEQ/gt/disparity/NNNNNN.pfm for every frame.
void WriteGroundTruth(const std::string& sequence);

// The three files, and the dumps a run with output.dump [overlay, features, saliency] leaves:
// overlay/NNNNNN.png, saliency/NNNNNN.pfm and .png, features/disparity/NNNNNN.pfm.
void WriteRunFolder(const std::string& dir, const RunFiles& files);
// Only the three files (the dumps stay as they are).
void WriteRunFiles(const std::string& dir, const RunFiles& files);

// Puts the input into one file of `files`. The first byte picks the file: 'f' frames.jsonl,
// 's' summary.json, 'c' config.yaml, any other byte by its value modulo 3 in that order; the
// rest of the input is the file's content. Returns the file's name.
std::string ReplaceRunFile(const uint8_t* data, size_t size, RunFiles* files);
// The three files of `valid` in `dir`, with the input put into one of them (ReplaceRunFile).
void WriteFuzzedRunFiles(const uint8_t* data, size_t size, const RunFiles& valid,
                         const std::string& dir);

}  // namespace attend::fuzz
