// The files of the skin model (docs/SKIN.md): the model file that `attend skin-train` writes
// and every skin feature reads, and the labelled training data (UCI text, image and mask).
#pragma once

#include <functional>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "colour/skin_model.h"

namespace attend {

// Reads a model file (keys: mean [t, s]; covariance [a, b, b, c] row-major; threshold; and an
// optional `training:` block with the provenance). Missing file, missing key, unknown key,
// wrong type or an invalid model: ConfigError naming the file, key and line.
SkinModel LoadSkinModel(const std::string& path);
// Writes the model as YAML with comments that say what each key means, every number written
// so that it reads back exactly. The file is written beside `path` and renamed into place, so
// `path` is never left half-written. OutputError when the file cannot be written.
void SaveSkinModel(const SkinModel& model, const std::string& path);

// Labelled chrominance samples.
struct SkinSamples {
  std::vector<cv::Vec2f> skin;     // (T, S)
  std::vector<cv::Vec2f> nonskin;  // (T, S)
};

// Receives samples one at a time, in the order they are read.
using SkinSampleSink = std::function<void(const cv::Vec2f& ts, bool skin)>;

// Appends the samples of the `B G R label` text format (label 1 skin, 2 not skin; the UCI Skin
// Segmentation data set): one sample a line, four integers separated by spaces or tabs, blank
// lines ignored. A malformed line: InputError naming the file and line; a file without
// samples: InputError.
void ReadSkinText(const std::string& path, SkinSamples* samples);
void ReadSkinText(const std::string& path, const SkinSampleSink& sink);
// Appends every pixel of an 8-bit colour image with its mask (read as grey, non-zero = skin),
// in raster order. Unreadable files or different sizes: InputError naming the file.
void ReadSkinImagePair(const std::string& image_path, const std::string& mask_path,
                       SkinSamples* samples);
void ReadSkinImagePair(const std::string& image_path, const std::string& mask_path,
                       const SkinSampleSink& sink);

// One data item of `attend skin-train`: a folder with images/ and masks/ (every image with the
// mask of the same stem, in order of the stems), a `B G R label` text file, or IMAGE:MASK (the
// split at the first colon that leaves an existing image, so paths may hold colons).
// InputError naming the item and the file.
void ReadSkinData(const std::string& item, const SkinSampleSink& sink);

}  // namespace attend
