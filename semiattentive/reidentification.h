// Re-identification (not in the thesis): an embedding of what a person looks like, from a
// network trained to tell people apart (OSNet x0.25 on MSMT17, docs/MODELS.md), read by
// OpenCV's cv::dnn. Two crops of one person give embeddings of high cosine similarity, two
// people's lower, whatever their pose and the light, which the colour histogram and the grey
// template of ObjectAppearance (semiattentive/object_files.h) do not manage in a crowd of
// dark coats.
//
// The crop is the box resized to the network's input (`width` x `height`, OSNet's 128 x 256),
// in RGB scaled to [0, 1] and normalised with ImageNet's mean (0.485, 0.456, 0.406) and
// standard deviation (0.229, 0.224, 0.225), as torchreid trains it. The output, one vector,
// is scaled to unit length.
#pragma once

#include <memory>
#include <opencv2/core.hpp>
#include <string>

#include "util/option_fields.h"

namespace attend {

namespace cvextra {
class DnnNet;
}  // namespace cvextra

// attention.appearance*: the embedding network and how often a target's is taken.
struct AppearanceOptions {
  std::string model;  // the network file; "": no embedding (the model-free appearance)
  int width = 128, height = 256;  // the network's input, px
  // A followed target's embedding is taken again every this many frames it is kept on its
  // object (blended into its own as the rest of its appearance is,
  // semiattentive/followed_targets.h); a new target's and a re-anchoring detection's at once.
  int every = 5;
  std::string Check() const;
  static const OptionFields<AppearanceOptions>& Fields();
};

class Reidentifier {
 public:
  // Reads the network at `model` (a resolved path) and checks that it gives one vector for
  // one crop. cv::dnn cannot read it or it gives something else: InputError (exit status 3)
  // naming `where` (the configuration key's place), the file and what was found.
  static std::unique_ptr<Reidentifier> Load(const AppearanceOptions& options,
                                            const std::string& where);
  ~Reidentifier();

  // The unit-length embedding (CV_32FC1, 1 x D) of `bgr`'s pixels in `box` (clipped to the
  // image); empty when nothing of the box is inside.
  cv::Mat Embed(const cv::Mat& bgr, const cv::Rect& box);
  int dimensions() const { return dimensions_; }

 private:
  Reidentifier(const AppearanceOptions& options, std::unique_ptr<cvextra::DnnNet> net);
  cv::Mat Forward(const cv::Mat& crop);

  AppearanceOptions options_;
  std::unique_ptr<cvextra::DnnNet> net_;
  int dimensions_ = 0;
  cv::Mat resized_, rgb_, normalised_;
  std::vector<cv::Mat> outputs_;
};

// The cosine similarity of two unit-length embeddings, clipped at 0; 0 when either is empty.
double EmbeddingSimilarity(const cv::Mat& a, const cv::Mat& b);

}  // namespace attend
