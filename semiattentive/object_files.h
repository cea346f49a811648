// Object files: the memory of attended objects that are no longer tracked (not in
// the thesis, whose stage forgets a target when its tracker does).
//
// A target that ends (its tracker lost it, or it was released for any reason but being a
// duplicate of another target) leaves a file for `memory_frames` frames: its last good box, its
// velocity and its appearance (an HSV histogram over its mask and a small grey template of its
// box, both taken from the frames in which it was found). While remembered, the object's
// predicted box moves with that velocity (slowing down, since people stop and turn), and its
// inhibition follows the prediction and fades linearly to nothing over `memory_frames`. A new
// target whose box lies within the position gate around a file's predicted box, of a similar
// size, and whose appearance matches the file's (`min_similarity`) resumes that object under
// its old id instead of being a new target; the best match by appearance wins, each file at
// most once.
//
//   ObjectFiles files(options);
//   files.Age();                                   // once a frame, before anything else
//   files.Remember(id, box, velocity, appearance, skin, label);
//   const int file = files.Match(box, appearance, skin);  // -1: a new object
//   if (file >= 0) { const ObjectFile resumed = files.Take(file); ... }
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "util/option_fields.h"

namespace attend {

struct ObjectFileOptions {
  // Frames a file is kept; 0: no object files (the thesis's stage).
  int memory_frames = 0;
  // The position gate: a new target's centre within this many of the remembered box's sides
  // (per axis) of the predicted centre, plus the distance the object could have walked while
  // unseen at its last speed.
  float gate = 1.0f;
  // The new box's width and height within this factor of the remembered ones.
  float max_size_ratio = 1.8f;
  // Appearance similarity (ObjectAppearance::Similarity) at least this.
  float min_similarity = 0.6f;
  // Each frame unseen, the remembered velocity is multiplied by this.
  float velocity_decay = 0.9f;
  // Attention moves on: a target found for this many seconds of the sequence's frame rate
  // since it was started (or resumed) is released ("dwell") into its object file, whose fading
  // inhibition keeps it from being attended again at once. 0: never; a target is held while it
  // is salient (the thesis's rule).
  float dwell_s = 0.f;
  // "" when valid; otherwise names the field and the broken constraint.
  std::string Check() const;
  static const OptionFields<ObjectFileOptions>& Fields();
};

// What an object looked like: a hue-saturation-value histogram of its pixels (mass 1; value
// too, since the clothes of people in a street are often greys, whose hue is noise) and its
// box's grey image at a fixed size (zero mean, unit norm), both blended over the frames it was
// seen.
struct ObjectAppearance {
  cv::Mat histogram;  // CV_32FC1, kHueBins x kSaturationBins x kValueBins
  cv::Mat grey;       // CV_32FC1, kTemplateWidth x kTemplateHeight
  // The template's root-mean-square contrast in grey levels before it was normalised: a
  // plain object's template is noise, and its correlation says nothing.
  float contrast = 0.f;
  static constexpr float kMinContrast = 4.f;
  // A re-identification network's unit-length embedding (semiattentive/reidentification.h),
  // blended over the frames it was taken in and scaled back to unit length; empty without one.
  cv::Mat embedding;

  static constexpr int kHueBins = 8, kSaturationBins = 4, kValueBins = 4;
  static constexpr int kTemplateWidth = 12, kTemplateHeight = 24;

  bool empty() const { return histogram.empty(); }
  // From the pixels of `mask` (CV_8UC1, frame size) in `bgr`, within `box`.
  static ObjectAppearance Of(const cv::Mat& bgr, const cv::Mat& mask, const cv::Rect& box);
  // Moves this appearance towards `seen` by `rate` (0: keep, 1: replace); an empty one is
  // replaced.
  void Blend(const ObjectAppearance& seen, float rate);
  // In [0, 1]: the embeddings' cosine similarity clipped at 0 when both have one; otherwise the
  // mean of the histograms' intersection and the templates' correlation clipped at 0, or the
  // intersection alone when either template has less than kMinContrast. 0 when either is
  // empty.
  double Similarity(const ObjectAppearance& other) const;
};

struct ObjectFile {
  int id = 0;
  cv::Rect box;          // where it was last seen
  cv::Point2f velocity;  // pixels a frame, when it was last seen
  int absent = 0;        // frames since it was last seen
  ObjectAppearance appearance;
  bool skin = false;
  std::string label;
  // Where it is expected `absent` frames after it was last seen.
  cv::Rect Predicted(float velocity_decay) const;
};

class ObjectFiles {
 public:
  explicit ObjectFiles(const ObjectFileOptions& options) : options_(options) {}

  bool enabled() const { return options_.memory_frames > 0; }
  // One frame passes: every file is a frame older; files older than memory_frames go.
  void Age();
  // Keeps a file on an object that ended (nothing when disabled).
  void Remember(ObjectFile file);
  // The file a new target with this box and appearance resumes: the index of the most similar
  // file that passes the gates, or -1.
  int Match(const cv::Rect& box, const ObjectAppearance& appearance, bool skin) const;
  // Removes and returns file `index`.
  ObjectFile Take(int index);
  // Adds each file's fading inhibition (1 - absent / (memory_frames + 1)) over its predicted
  // box to `inhibition` (CV_32FC1), keeping the larger value where they overlap.
  void Inhibit(cv::Mat* inhibition) const;
  // The predicted boxes, clipped to `image` (where attention may look for them).
  std::vector<cv::Rect> PredictedBoxes(const cv::Rect& image) const;

  const std::vector<ObjectFile>& files() const { return files_; }
  const ObjectFileOptions& options() const { return options_; }

 private:
  ObjectFileOptions options_;
  std::vector<ObjectFile> files_;
};

}  // namespace attend
