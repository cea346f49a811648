// The `dnn` backend of the top-down channels (features/detectors.h): a pretrained detector
// network that OpenCV's cv::dnn reads (Darknet's cfg and weights, ONNX, ...), on the CPU. Not in
// the thesis. docs/MODELS.md lists the networks it was measured with and where to get them.
//
// The network sees the image padded on the right and at the bottom to multiples of 32 (the
// coarsest stride of the detectors' grids), at the scale the channel chose: the whole frame
// with its longer side at `input_size`, a crop where attention looked at the same scale
// times `crop_zoom` (features/detectors.h). So a crop costs its share of the frame's pixels,
// and the network's pixels a frame are what `summary.json` reports as searched.
//
// A model path that is not absolute is looked for next to the configuration file, in
// $ATTEND_MODELS, in the current folder and in the bundled files' folder. The network is read
// once, when the feature is made, and run once on a blank input to check that its outputs
// fit the decoder (features/dnn_decoders.h).
#pragma once

#include <memory>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "features/dnn_decoders.h"
#include "features/feature_map.h"
#include "util/option_fields.h"

namespace attend {

namespace cvextra {
class DnnNet;
}  // namespace cvextra

class ParamBlock;

struct DnnDetectorOptions {
  std::string model;   // the network: .onnx, .weights (Darknet, with `config`), ...
  std::string config;  // Darknet's .cfg; "" for formats in one file
  DnnDecoder decoder = DnnDecoder::kYolox;
  int input_size = 416;    // the whole frame's longer side at the network's input, px
  double crop_zoom = 1.0;  // a crop's scale against the whole frame's
  // The classes that count: indices, or names of the `names` file; all of a one-class network.
  std::vector<std::string> classes = {"0"};
  std::string names;    // the class names, one a line (COCO's coco.names); "" none
  double score = 0.3;   // the least score a box keeps
  double nms = 0.45;    // boxes of one class overlapping more than this IoU: the best is kept
  std::string Check() const;
  static const OptionFields<DnnDetectorOptions>& Fields();
  static const std::vector<std::string>& Decoders();
  // The defaults of `decoder`: YOLOX 416 px, Darknet's Yolo-Fastest 320 px, YuNet 320 px.
  static DnnDetectorOptions ForDecoder(DnnDecoder decoder);
};

// Where a model file named in a configuration is: `path` if absolute, else the first of the
// configuration file's folder (`config_file`), $ATTEND_MODELS, the current folder and
// `home`; "" when in none. `places` (may be null) gets the folders looked in.
std::string FindModelFile(const std::string& path, const std::string& config_file,
                          const std::string& home, std::string* places);

class DnnDetector {
 public:
  // Reads the options' files from the channel's parameter block `params` (paths resolved by
  // FindModelFile) and checks the network. A missing file: ConfigError (exit status 2) naming
  // the key, the path, the folders looked in and docs/MODELS.md. A file cv::dnn cannot read:
  // InputError (exit status 3) with cv::dnn's message. Outputs that do not fit the decoder:
  // InputError naming the shapes expected and found. `label`: the label of every box; "" for
  // the class's name (or its index when there is no names file).
  static std::unique_ptr<DnnDetector> Load(const DnnDetectorOptions& options,
                                           const ParamBlock& params, const FeatureSetup& setup,
                                           const std::string& label);
  ~DnnDetector();

  // The objects in `image` (8-bit BGR, any size), at its own scale: boxes in its pixels. The
  // image is padded to multiples of 32; `padded` (may be null) gets the padded size.
  void Detect(const cv::Mat& image, std::vector<Detection>* found, cv::Size* padded = nullptr);
  const DnnDetectorOptions& options() const { return options_; }

  // The image padded on the right and at the bottom to multiples of 32 (with the grey 114
  // that YOLOX was trained with), at least 32 x 32.
  static cv::Size PaddedSize(cv::Size size);

 private:
  DnnDetector(const DnnDetectorOptions& options, std::unique_ptr<cvextra::DnnNet> net,
              std::vector<int> classes, std::vector<std::string> labels);
  void Forward(const cv::Mat& padded, DnnOutputs* outputs);

  DnnDetectorOptions options_;
  std::unique_ptr<cvextra::DnnNet> net_;
  std::vector<int> classes_;
  std::vector<std::string> labels_;  // by class index; one entry: every class's
  cv::Mat padded_;
  DnnOutputs outputs_;
};

}  // namespace attend
