#include "features/dnn_detector.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <opencv2/imgproc.hpp>

#include "config/param_block.h"
#include "config/read_fields.h"
#include "util/enum_table.h"
#include "util/error.h"
#include "util/opencv_extra.h"
#include "util/strings.h"

namespace attend {

namespace {

namespace fs = std::filesystem;

constexpr int kCoarsestStride = 32;

const char* const kModelsHint =
    "docs/MODELS.md says where to get each model (scripts/get_models.sh DIR downloads them; "
    "then set ATTEND_MODELS=DIR)";

constexpr EnumTable<DnnDecoder, 3> kDecoders = {{{
    {DnnDecoder::kDarknet, "darknet"},
    {DnnDecoder::kYolox, "yolox"},
    {DnnDecoder::kYunet, "yunet"},
}}};

// How each decoder's network is fed: pixel scale, colour order and the padding's grey.
struct Feeding {
  double scale;
  bool swap_rb;
  int pad;
};

Feeding FeedingOf(DnnDecoder decoder) {
  switch (decoder) {
    case DnnDecoder::kDarknet:
      return {1.0 / 255.0, true, 114};  // RGB in [0, 1]
    case DnnDecoder::kYolox:
      return {1.0, false, 114};  // BGR 0-255, YOLOX's letterbox grey
    case DnnDecoder::kYunet:
      return {1.0, false, 0};  // BGR 0-255, padded with black as OpenCV's FaceDetectorYN does
  }
  return {1.0, false, 0};
}

// The class names of a names file, one a line (blank lines kept as "").
std::vector<std::string> ReadNames(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::string> names;
  std::string line;
  while (std::getline(in, line)) {
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
    names.push_back(line);
  }
  return names;
}

// The model file at `key` resolved, or a ConfigError naming it and where it was looked for.
std::string ResolveModel(const ParamBlock& params, const FeatureSetup& setup,
                         const std::string& key, const std::string& path) {
  if (path.empty()) {
    params.Fail(key, std::string("must name a model file; ") + kModelsHint);
  }
  std::string places;
  const std::string found = FindModelFile(path, params.source(), setup.home, &places);
  if (found.empty()) {
    params.Fail(key, "no such file: " + path +
                         (places.empty() ? "" : " (looked in " + places + ")") + "; " +
                         kModelsHint);
  }
  if (fs::is_directory(found)) params.Fail(key, found + ": is a folder, not a model file");
  return found;
}

// The class indices of `classes` (indices or names of `names`).
std::vector<int> ClassIndices(const ParamBlock& params, const std::vector<std::string>& classes,
                              const std::vector<std::string>& names) {
  std::vector<int> indices;
  for (const std::string& text : classes) {
    char* end = nullptr;
    const long index = std::strtol(text.c_str(), &end, 10);
    if (!text.empty() && *end == '\0') {
      if (index < 0 || index > 100000) params.Fail("classes", "class index out of range: " + text);
      indices.push_back(static_cast<int>(index));
      continue;
    }
    const auto found = std::find(names.begin(), names.end(), text);
    if (found == names.end()) {
      params.Fail("classes", "'" + text + "' is neither a class index nor a name of " +
                                 (names.empty() ? std::string("the names file (none given: set "
                                                              "`names`)")
                                                : std::string("the names file")));
    }
    indices.push_back(static_cast<int>(found - names.begin()));
  }
  return indices;
}

}  // namespace

const OptionFields<DnnDetectorOptions>& DnnDetectorOptions::Fields() {
  using O = DnnDetectorOptions;
  // `model`, `config` and `names` are paths the detector resolves itself (FindModelFile).
  static const OptionFields<DnnDetectorOptions> fields = {
      {"model", &O::model, "the network file (.onnx, Darknet .weights, ...); docs/MODELS.md"},
      {"config", &O::config, "Darknet's .cfg beside its .weights; empty for one-file formats"},
      {"decoder", EnumField<&O::decoder, kDecoders>(),
       "the network's output layout: darknet, yolox or yunet"},
      {"input_size", &O::input_size, Range::Closed(32, 4096),
       "the whole frame's longer side at the network's input, px (a multiple of 32)"},
      {"crop_zoom", &O::crop_zoom, Range::Closed(0.25, 8),
       "a crop around attention at this times the whole frame's scale"},
      {"classes", &O::classes, "the classes that count: indices or names of the names file"},
      {"names", &O::names, "the class names file, one a line; empty: none"},
      {"score", &O::score, Range::AboveUpTo(0, 1), "the least score a box keeps"},
      {"nms", &O::nms, Range::AboveUpTo(0, 1),
       "boxes of one class overlapping more than this IoU: the best is kept"}};
  return fields;
}

const std::vector<std::string>& DnnDetectorOptions::Decoders() {
  static const std::vector<std::string> names = kDecoders.Names();
  return names;
}

DnnDetectorOptions DnnDetectorOptions::ForDecoder(DnnDecoder decoder) {
  DnnDetectorOptions options;
  options.decoder = decoder;
  if (decoder != DnnDecoder::kYolox) options.input_size = 320;
  return options;
}

std::string DnnDetectorOptions::Check() const {
  const std::string error = CheckFieldRanges(*this, Fields());
  if (!error.empty()) return error;
  if (input_size % kCoarsestStride != 0) return "input_size must be a multiple of 32";
  if (decoder != DnnDecoder::kYunet && classes.empty()) {
    return "classes must name at least one class";
  }
  return "";
}

std::string FindModelFile(const std::string& path, const std::string& config_file,
                          const std::string& home, std::string* places) {
  std::vector<fs::path> folders;
  if (!path.empty() && !fs::path(path).is_absolute()) {
    if (!config_file.empty() && fs::is_regular_file(config_file)) {
      // Absolute, so that a configuration named without a folder names its folder in messages.
      folders.push_back(fs::absolute(config_file).parent_path());
    }
    if (const char* models = std::getenv("ATTEND_MODELS"); models != nullptr && *models != '\0') {
      folders.emplace_back(models);
    }
    folders.emplace_back(".");
    if (!home.empty()) folders.emplace_back(home);
  }
  if (places != nullptr) {
    std::vector<std::string> texts;
    for (const fs::path& folder : folders) {
      texts.push_back(folder == "." ? "the current folder" : folder.string());
    }
    *places = Join(texts, ", ");
  }
  if (path.empty()) return "";
  if (fs::path(path).is_absolute()) return fs::exists(path) ? path : "";
  for (const fs::path& folder : folders) {
    const fs::path candidate = folder == "." ? fs::path(path) : folder / path;
    if (fs::exists(candidate)) return candidate.string();
  }
  return "";
}

std::unique_ptr<DnnDetector> DnnDetector::Load(const DnnDetectorOptions& given,
                                               const ParamBlock& params, const FeatureSetup& setup,
                                               const std::string& label) {
  DnnDetectorOptions options = given;
  const std::string error = options.Check();
  if (!error.empty()) params.FailCheck(error);
  options.model = ResolveModel(params, setup, "model", options.model);
  if (!options.config.empty()) {
    options.config = ResolveModel(params, setup, "config", options.config);
  }
  std::vector<std::string> names;
  if (!options.names.empty()) {
    options.names = ResolveModel(params, setup, "names", options.names);
    names = ReadNames(options.names);
  }
  const std::vector<int> classes = options.decoder == DnnDecoder::kYunet
                                       ? std::vector<int>{}
                                       : ClassIndices(params, options.classes, names);
  std::vector<std::string> labels;
  if (!label.empty()) {
    labels = {label};
  } else {
    const int largest = classes.empty() ? 0 : *std::max_element(classes.begin(), classes.end());
    const int count = std::max<int>(static_cast<int>(names.size()), largest + 1);
    for (int c = 0; c < count; ++c) {
      labels.push_back(c < static_cast<int>(names.size()) && !names[c].empty() ? names[c]
                                                                              : std::to_string(c));
    }
  }
  std::unique_ptr<cvextra::DnnNet> net;
  const std::string files =
      options.model + (options.config.empty() ? "" : " with " + options.config);
  try {
    net = cvextra::Get("the dnn backend (OpenCV's dnn)").ReadNet(options.model, options.config);
  } catch (const cv::Exception& e) {
    throw InputError(params.Where("model") + ": " + files + ": cv::dnn cannot read it: " + e.err);
  }
  std::unique_ptr<DnnDetector> detector(
      new DnnDetector(options, std::move(net), classes, std::move(labels)));
  // One pass on a blank input, to check the outputs' layout now rather than on a frame.
  const cv::Size probe(options.input_size, options.input_size);
  DnnOutputs outputs;
  try {
    detector->Forward(cv::Mat(probe, CV_8UC3, cv::Scalar::all(FeedingOf(options.decoder).pad)),
                      &outputs);
  } catch (const cv::Exception& e) {
    throw InputError(params.Where("model") + ": " + files +
                     ": cv::dnn cannot run it on a 3-channel image: " + e.err);
  }
  const int max_class = classes.empty() ? 0 : *std::max_element(classes.begin(), classes.end());
  const std::string mismatch = CheckDnnOutputs(options.decoder, outputs, probe, max_class);
  if (!mismatch.empty()) {
    throw InputError(params.Where("model") + ": " + files + ": its outputs do not fit decoder " +
                     kDecoders.Name(options.decoder) + ": " + mismatch);
  }
  return detector;
}

DnnDetector::DnnDetector(const DnnDetectorOptions& options, std::unique_ptr<cvextra::DnnNet> net,
                         std::vector<int> classes, std::vector<std::string> labels)
    : options_(options),
      net_(std::move(net)),
      classes_(std::move(classes)),
      labels_(std::move(labels)) {}

DnnDetector::~DnnDetector() = default;

cv::Size DnnDetector::PaddedSize(cv::Size size) {
  const auto up = [](int side) {
    return std::max(kCoarsestStride, (side + kCoarsestStride - 1) / kCoarsestStride *
                                         kCoarsestStride);
  };
  return cv::Size(up(size.width), up(size.height));
}

void DnnDetector::Forward(const cv::Mat& padded, DnnOutputs* outputs) {
  const Feeding feeding = FeedingOf(options_.decoder);
  net_->Forward(padded, feeding.scale, cv::Scalar(), feeding.swap_rb, &outputs->values);
  outputs->names = net_->OutputNames();
}

void DnnDetector::Detect(const cv::Mat& image, std::vector<Detection>* found, cv::Size* padded) {
  CV_Assert(image.type() == CV_8UC3);
  found->clear();
  const cv::Size size = PaddedSize(image.size());
  if (padded != nullptr) *padded = size;
  const Feeding feeding = FeedingOf(options_.decoder);
  cv::copyMakeBorder(image, padded_, 0, size.height - image.rows, 0, size.width - image.cols,
                     cv::BORDER_CONSTANT, cv::Scalar::all(feeding.pad));
  Forward(padded_, &outputs_);
  std::vector<DnnBox> boxes = DecodeDnnOutputs(options_.decoder, outputs_, size, classes_,
                                               static_cast<float>(options_.score));
  // Non-maximum suppression within each class, the best first.
  std::stable_sort(boxes.begin(), boxes.end(),
                   [](const DnnBox& a, const DnnBox& b) { return a.score > b.score; });
  const cv::Rect2f inside(0.f, 0.f, static_cast<float>(image.cols),
                          static_cast<float>(image.rows));
  std::vector<DnnBox> kept;
  for (const DnnBox& box : boxes) {
    const bool overlaps = std::any_of(kept.begin(), kept.end(), [&](const DnnBox& other) {
      if (other.class_index != box.class_index) return false;
      const float shared = (other.box & box.box).area();
      return shared > options_.nms * (other.box.area() + box.box.area() - shared);
    });
    if (overlaps) continue;
    kept.push_back(box);
    const cv::Rect2f clipped = box.box & inside;
    if (clipped.width < 1.f || clipped.height < 1.f) continue;
    const std::string& label =
        labels_.size() == 1 ? labels_[0]
                            : labels_[std::min<size_t>(box.class_index, labels_.size() - 1)];
    found->push_back({cv::Rect(cvRound(clipped.x), cvRound(clipped.y), cvRound(clipped.width),
                               cvRound(clipped.height)),
                      label, std::clamp(box.score, 1e-6f, 1.f)});
  }
}

}  // namespace attend
