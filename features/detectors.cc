#include "features/detectors.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <opencv2/imgproc.hpp>

#include "config/read_fields.h"
#include "features/dnn_detector.h"
#include "util/box.h"
#include "util/enum_table.h"
#include "util/opencv_extra.h"

namespace attend {

namespace {

namespace fs = std::filesystem;

// Boxes of one object found in overlapping crops (or at neighbouring scales that the
// detector's own grouping kept apart) overlap by more than this.
constexpr double kMergeIou = 0.5;

const char* const kOpencvDataHint =
    "the cascades come with Debian's package opencv-data (scripts/install_deps.sh installs it)";

// The object box inside a detection window: `width` and `height` shares of it, centred.
cv::Rect ObjectInWindow(const cv::Rect& window, double width, double height) {
  const double w = window.width * width, h = window.height * height;
  const double x = window.x + 0.5 * (window.width - w), y = window.y + 0.5 * (window.height - h);
  return cv::Rect(cvRound(x), cvRound(y), std::max(1, cvRound(w)), std::max(1, cvRound(h)));
}

// The pyramid levels (OpenCV's nlevels) whose window holds objects of at most
// `max_object_height` px: level k holds objects of object_height x scale^k.
// cv::HOGDescriptor::DEFAULT_NLEVELS.
constexpr int kHogDefaultLevels = 64;

int LevelsUpTo(double max_object_height, double object_height, double scale) {
  if (max_object_height <= 0.0) return kHogDefaultLevels;
  if (max_object_height < object_height) return 0;
  const double levels = std::floor(std::log(max_object_height / object_height) / std::log(scale));
  return std::min<int>(kHogDefaultLevels, static_cast<int>(levels) + 1);
}

class HogPeopleSearch {
 public:
  explicit HogPeopleSearch(const HogPeopleOptions& options)
      : options_(options),
        hog_(cvextra::Get("the people channel (OpenCV's HOG)")
                 .CreateHog(options_.model == "daimler")),
        window_(hog_->WindowSize()) {}

  void Run(const cv::Mat& image, double max_object_height, std::vector<Detection>* found) {
    found->clear();
    if (image.cols < window_.width || image.rows < window_.height) return;
    const int levels =
        LevelsUpTo(max_object_height, window_.height * options_.box_height, options_.scale);
    if (levels == 0) return;
    hog_->Detect(image, levels, options_.hit_threshold, cv::Size(options_.stride, options_.stride),
                 options_.scale, options_.min_neighbours, &windows_, &weights_);
    for (size_t i = 0; i < windows_.size(); ++i) {
      found->push_back({ObjectInWindow(windows_[i], options_.box_width, options_.box_height),
                        "person", ScoreToConfidence(weights_[i])});
    }
  }

 private:
  HogPeopleOptions options_;
  std::unique_ptr<cvextra::HogDetector> hog_;
  cv::Size window_;
  std::vector<cv::Rect> windows_;
  std::vector<double> weights_;
};

class CascadeSearch {
 public:
  CascadeSearch(std::unique_ptr<cvextra::Cascade> cascade, const FaceCascadeOptions& options)
      : cascade_(std::move(cascade)), options_(options) {}

  void Run(const cv::Mat& image, double max_object_height, std::vector<Detection>* found) {
    found->clear();
    const cv::Size window = cascade_->OriginalWindowSize();
    if (image.cols < window.width || image.rows < window.height) return;
    if (image.channels() == 3) {
      cv::cvtColor(image, grey_, cv::COLOR_BGR2GRAY);
    } else {
      image.copyTo(grey_);
    }
    cv::equalizeHist(grey_, grey_);
    cv::Size max_size;
    if (max_object_height > 0.0) {
      if (max_object_height < window.height) return;
      const double grow = max_object_height / window.height;
      max_size = cv::Size(cvFloor(window.width * grow), cvFloor(max_object_height));
    }
    cascade_->Detect(grey_, options_.scale, options_.min_neighbours, window, max_size, &boxes_,
                     &levels_, &weights_);
    for (size_t i = 0; i < boxes_.size(); ++i) {
      found->push_back({boxes_[i], "face", ScoreToConfidence(weights_[i])});
    }
  }

 private:
  std::unique_ptr<cvextra::Cascade> cascade_;
  FaceCascadeOptions options_;
  cv::Mat grey_;
  std::vector<cv::Rect> boxes_;
  std::vector<int> levels_;
  std::vector<double> weights_;
};

class ObjectFeature final : public FeatureMap {
 public:
  explicit ObjectFeature(std::unique_ptr<ObjectChannel> channel) : channel_(std::move(channel)) {}
  void BeginSequence(const SequenceStart&) override { channel_->Restart(); }
  void Compute(const FrameContext& context, cv::Mat* out) override {
    channel_->Compute(context.left(), context.AttentionRegions(), out);
  }
  const std::vector<Detection>& detections() const override { return channel_->detections(); }
  double searched_pixels() const override { return channel_->last_searched_pixels(); }
  bool ReadsAttentionRegions() const override { return channel_->reads_regions(); }

 private:
  std::unique_ptr<ObjectChannel> channel_;
};

// The keys both channels share; `defaults` are the channel's own.
ObjectChannelOptions ReadChannelOptions(const ParamBlock& params,
                                        const ObjectChannelOptions& defaults) {
  ObjectChannelOptions options = defaults;
  ReadFields(params, ObjectChannelOptions::Fields(), &options);
  const std::string error = options.Check();
  if (!error.empty()) params.FailCheck(error);
  return options;
}

// A channel around a network (features/dnn_detector.h): `decoder` unless the block names one,
// labelled `label` ("" for the class names). `window`: the aspect of the crops around
// attention and the smallest searched.
std::unique_ptr<FeatureMap> MakeNetworkChannel(const ParamBlock& params, const FeatureSetup& setup,
                                               const ObjectChannelOptions& channel,
                                               DnnDecoder decoder, const std::string& label,
                                               cv::Size window) {
  DnnDetectorOptions dnn;
  ReadFields(params, {FieldNamed(DnnDetectorOptions::Fields(), "decoder")}, &dnn);
  dnn = DnnDetectorOptions::ForDecoder(params.Has("decoder") ? dnn.decoder : decoder);
  ReadFields(params, DnnDetectorOptions::Fields(), &dnn);
  std::shared_ptr<DnnDetector> detector = DnnDetector::Load(dnn, params, setup, label);
  DetectorGeometry geometry{window, static_cast<double>(window.height), dnn.input_size,
                            dnn.crop_zoom};
  ObjectSearch search = [detector](const cv::Mat& image, double, std::vector<Detection>* found) {
    detector->Detect(image, found);
  };
  return std::make_unique<ObjectFeature>(
      std::make_unique<ObjectChannel>(channel, geometry, label, std::move(search)));
}

constexpr EnumTable<DetectionShape, 2> kShapes = {{{
    {DetectionShape::kBox, "box"},
    {DetectionShape::kGaussian, "gaussian"},
}}};

constexpr EnumTable<DetectorGate, 2> kGates = {{{
    {DetectorGate::kAttended, "attended"},
    {DetectorGate::kFrame, "frame"},
}}};

}  // namespace

const OptionFields<ObjectChannelOptions>& ObjectChannelOptions::Fields() {
  using O = ObjectChannelOptions;
  static const OptionFields<ObjectChannelOptions> fields = {
      {"gate", EnumField<&O::gate, kGates>(),
       "attended: search where attention looked; frame: the whole frame"},
      {"margin", &O::margin, Range::Closed(0, 4),
       "a looked-at region's crop grows by this times its size on each side"},
      {"every", &O::every, Range::Closed(1, 1000), "frame gate: search every this many frames"},
      {"scan_every", &O::scan_every, Range::Closed(0, 1000),
       "attended gate: also search the whole frame every this many frames; 0: never"},
      {"min_height", &O::min_height, Range::Closed(4, 10000), "smallest object searched for, px"},
      {"max_height", &O::max_height, Range::Closed(0, 10000),
       "largest object searched for, px; 0: no bound"},
      {"blur", &O::blur, Range::Closed(0, 1),
       "sigma of a Gaussian on the map, share of the larger side; 0: none"},
      {"shape", EnumField<&O::shape, kShapes>(),
       "each detection in the map: box, filled with its confidence; gaussian, a Gaussian over "
       "its box peaking at its confidence"},
      {"shape_sigma", &O::shape_sigma, Range::AboveUpTo(0, 4),
       "gaussian shape: sigma, share of the box's width and height"},
      {"shape_centre_y", &O::shape_centre_y, Range::Closed(0, 1),
       "gaussian shape: the centre's height in the box, share from its top"},
      {"size_power", &O::size_power, Range::Closed(-4, 4),
       "each detection's value: its confidence x (box height / map height) to this power; 0: "
       "the confidence"}};
  return fields;
}

DetectionPaint ObjectChannelOptions::Paint() const {
  return {shape, shape_sigma, shape_centre_y, size_power, blur};
}

std::string ObjectChannelOptions::Check() const {
  const std::string error = CheckFieldRanges(*this, Fields());
  if (!error.empty()) return error;
  if (max_height != 0 && max_height < min_height) {
    return "max_height must be 0 or at least min_height (" + std::to_string(min_height) + ")";
  }
  return "";
}

const OptionFields<HogPeopleOptions>& HogPeopleOptions::Fields() {
  using O = HogPeopleOptions;
  static const OptionFields<HogPeopleOptions> fields = {
      {"model", &O::model, "default: 64x128 (INRIA); daimler: 48x96", &HogPeopleOptions::Models},
      {"hit_threshold", &O::hit_threshold, Range::Closed(-10, 10),
       "SVM margin a window needs to count as a hit"},
      {"min_neighbours", &O::min_neighbours, Range::Closed(0, 100),
       "a detection needs more than this many overlapping hit windows"},
      {"scale", &O::scale, Range::AboveUpTo(1, 2), "step between pyramid levels"},
      {"stride", &O::stride, Range::Closed(8, 64), "window stride, px, a multiple of 8"},
      {"box_width", &O::box_width, Range::AboveUpTo(0, 2),
       "the person's share of the window's width; default 0.65 with model daimler"},
      {"box_height", &O::box_height, Range::AboveUpTo(0, 2),
       "the person's share of the window's height; default 0.97 with model daimler"}};
  return fields;
}

const std::vector<std::string>& HogPeopleOptions::Models() {
  static const std::vector<std::string> models = {"default", "daimler"};
  return models;
}

HogPeopleOptions HogPeopleOptions::ForModel(const std::string& model) {
  HogPeopleOptions options;
  options.model = model;
  if (model == "daimler") {
    options.box_width = 0.65;
    options.box_height = 0.97;
  }
  return options;
}

std::string HogPeopleOptions::Check() const {
  const std::string error = CheckFieldRanges(*this, Fields());
  if (!error.empty()) return error;
  // OpenCV's HOG moves the window in steps of its block stride, 8 px.
  if (stride % 8 != 0) return "stride must be a multiple of 8";
  return "";
}

const OptionFields<FaceCascadeOptions>& FaceCascadeOptions::Fields() {
  using O = FaceCascadeOptions;
  // `model` is a path the feature resolves itself (CreateFacesFeature).
  static const OptionFields<FaceCascadeOptions> fields = {
      {"model", &O::model, "the cascade file (Haar or LBP, OpenCV's XML format)"},
      {"min_neighbours", &O::min_neighbours, Range::Closed(0, 100),
       "a detection needs more than this many overlapping hits"},
      {"scale", &O::scale, Range::AboveUpTo(1, 2), "step between pyramid levels"}};
  return fields;
}

std::string FaceCascadeOptions::Check() const { return CheckFieldRanges(*this, Fields()); }

ObjectChannel::ObjectChannel(const ObjectChannelOptions& options, const DetectorGeometry& geometry,
                             std::string label, ObjectSearch search)
    : options_(options), geometry_(geometry), label_(std::move(label)), search_(std::move(search)) {
  const std::string error = options_.Check();
  ATTEND_CHECK(error.empty()) << error;
  ATTEND_CHECK(geometry_.window.width > 0 && geometry_.window.height > 0 &&
               geometry_.object_height > 0.0);
}

void ObjectChannel::Restart() {
  frames_since_search_ = -1;
  detections_.clear();
}

void ObjectChannel::Search(const cv::Mat& image, const cv::Rect& crop, double min_object,
                           double max_object, std::vector<Detection>* found) {
  const bool network = geometry_.network_side > 0;
  // A network sees the frame at one scale and a crop at that scale times its zoom; a
  // sliding-window detector's image is scaled so that the smallest object wanted fills the
  // window: its pyramid only shrinks.
  const bool whole = crop.width == image.cols && crop.height == image.rows;
  const double scale =
      network ? geometry_.network_side / static_cast<double>(std::max(image.cols, image.rows)) *
                    (whole ? 1.0 : geometry_.crop_zoom)
              : geometry_.object_height / min_object;
  const cv::Size size(std::max(1, cvRound(crop.width * scale)),
                      std::max(1, cvRound(crop.height * scale)));
  if (!network && (size.width < geometry_.window.width || size.height < geometry_.window.height)) {
    return;
  }
  cv::resize(image(crop), scaled_, size, 0, 0, scale < 1.0 ? cv::INTER_AREA : cv::INTER_LINEAR);
  ++last_searches_;
  last_searched_pixels_ += static_cast<double>(
      (network ? DnnDetector::PaddedSize(size) : size).area());
  search_(scaled_, max_object > 0.0 ? max_object * scale : 0.0, &scaled_found_);
  const cv::Rect frame(0, 0, image.cols, image.rows);
  for (const Detection& detection : scaled_found_) {
    const cv::Rect& box = detection.box;
    const cv::Rect box_in_frame =
        cv::Rect(cvRound(crop.x + box.x / scale), cvRound(crop.y + box.y / scale),
                 cvRound(box.width / scale), cvRound(box.height / scale)) &
        frame;
    if (box_in_frame.empty()) continue;
    // A network finds objects of every size: those outside the channel's heights go.
    if (network && (box_in_frame.height < options_.min_height ||
                    (max_object > 0.0 && box_in_frame.height > max_object))) {
      continue;
    }
    found->push_back(
        {box_in_frame, label_.empty() ? detection.label : label_, detection.confidence});
  }
}

void ObjectChannel::Compute(const cv::Mat& bgr, const std::vector<cv::Rect>& regions,
                            cv::Mat* map) {
  CV_Assert(!bgr.empty() && bgr.depth() == CV_8U);
  if (bgr.size() != last_size_) Restart();
  last_size_ = bgr.size();
  last_searches_ = 0;
  last_searched_pixels_ = 0.0;
  const double max_object = options_.max_height;
  if (options_.gate == DetectorGate::kFrame) {
    const bool due = frames_since_search_ < 0 || frames_since_search_ + 1 >= options_.every;
    if (due) {
      detections_.clear();
      Search(bgr, cv::Rect(0, 0, bgr.cols, bgr.rows), options_.min_height, max_object,
             &detections_);
      SuppressOverlaps(kMergeIou, &detections_);
      frames_since_search_ = 0;
    } else {
      ++frames_since_search_;
    }
  } else if (options_.scan_every > 0 &&
             (frames_since_search_ < 0 || frames_since_search_ + 1 >= options_.scan_every)) {
    // The glance at the whole scene: it covers every region too.
    detections_.clear();
    Search(bgr, cv::Rect(0, 0, bgr.cols, bgr.rows), options_.min_height, max_object,
           &detections_);
    SuppressOverlaps(kMergeIou, &detections_);
    frames_since_search_ = 0;
  } else {
    ++frames_since_search_;
    detections_.clear();
    searched_.clear();
    const cv::Rect frame(0, 0, bgr.cols, bgr.rows);
    for (const cv::Rect& region : regions) {
      const cv::Rect seen = region & frame;
      if (seen.empty()) continue;
      const cv::Rect crop = GateCrop(seen, options_.margin, geometry_.window, bgr.size());
      // The region is about the object: it is at least the region's height shrunk by the
      // margins (the region may be the object's box grown by attention's own margin).
      // A network's crops are searched at one scale whatever the region (their cost is their
      // area).
      const double min_object =
          geometry_.network_side > 0
              ? options_.min_height
              : std::max<double>(options_.min_height, seen.height / (1.0 + 2.0 * options_.margin));
      if (max_object > 0.0 && min_object > max_object) continue;
      // A target and its object file's prediction often give the same region.
      const bool repeated = std::any_of(searched_.begin(), searched_.end(), [&](const auto& done) {
        return done.first == crop && done.second == min_object;
      });
      if (repeated) continue;
      searched_.emplace_back(crop, min_object);
    }
    for (const auto& [crop, min_object] : MergeCrops(searched_, geometry_.object_height)) {
      Search(bgr, crop, min_object, max_object, &detections_);
    }
    SuppressOverlaps(kMergeIou, &detections_);
  }
  PaintDetections(detections_, options_.Paint(), bgr.size(), map);
}

std::vector<std::pair<cv::Rect, double>> MergeCrops(std::vector<std::pair<cv::Rect, double>> crops,
                                                    double object_height) {
  const auto cost = [object_height](const cv::Rect& crop, double min_object) {
    const double scale = object_height / min_object;
    return static_cast<double>(crop.area()) * scale * scale;
  };
  bool merged = true;
  while (merged) {
    merged = false;
    for (size_t i = 0; i < crops.size() && !merged; ++i) {
      for (size_t j = i + 1; j < crops.size() && !merged; ++j) {
        const auto& [a, a_min] = crops[i];
        const auto& [b, b_min] = crops[j];
        if ((a & b).empty()) continue;
        const cv::Rect joined = a | b;
        const double joined_min = std::min(a_min, b_min);
        if (cost(joined, joined_min) > cost(a, a_min) + cost(b, b_min)) continue;
        crops[i] = {joined, joined_min};
        crops.erase(crops.begin() + static_cast<std::ptrdiff_t>(j));
        merged = true;
      }
    }
  }
  return crops;
}

cv::Rect GateCrop(const cv::Rect& region, double margin, cv::Size window, cv::Size frame) {
  double w = region.width * (1.0 + 2.0 * margin);
  const double h = region.height * (1.0 + 2.0 * margin);
  // Wide enough for the window of an object as tall as the crop; never taller than the region
  // says: a wide, low region (a strip of a building's edge) holds no tall object, and
  // heightening it would search most of the frame.
  const double aspect = static_cast<double>(window.width) / window.height;
  if (w < h * aspect) w = h * aspect;
  const double cx = region.x + 0.5 * region.width, cy = region.y + 0.5 * region.height;
  const cv::Rect grown(cvRound(cx - 0.5 * w), cvRound(cy - 0.5 * h), cvRound(w), cvRound(h));
  return grown & cv::Rect(0, 0, frame.width, frame.height);
}

ObjectSearch MakeHogPeopleSearch(const HogPeopleOptions& options) {
  const std::string error = options.Check();
  ATTEND_CHECK(error.empty()) << error;
  auto search = std::make_shared<HogPeopleSearch>(options);
  return [search](const cv::Mat& image, double max_object_height, std::vector<Detection>* found) {
    search->Run(image, max_object_height, found);
  };
}

DetectorGeometry HogPeopleGeometry(const HogPeopleOptions& options) {
  const cv::Size window = options.model == "daimler" ? cv::Size(48, 96) : cv::Size(64, 128);
  return {window, window.height * options.box_height};
}

ObjectSearch MakeFaceCascadeSearch(const FaceCascadeOptions& options, const ParamBlock& params,
                                   const std::string& key, DetectorGeometry* geometry) {
  const std::string error = options.Check();
  ATTEND_CHECK(error.empty()) << error;
  // OpenCV reports a folder or an unreadable file as an empty cascade; say which it is.
  if (fs::is_directory(options.model)) {
    params.Fail(key, options.model + ": is a folder, not a cascade file; " + kOpencvDataHint);
  }
  if (!std::ifstream(options.model).good()) {
    params.Fail(key, options.model + ": cannot be read; " + kOpencvDataHint);
  }
  std::unique_ptr<cvextra::Cascade> cascade;
  try {
    cascade = cvextra::Get("the faces channel (OpenCV's cascades)").LoadCascade(options.model);
  } catch (const cv::Exception& e) {
    params.Fail(
        key, options.model + ": not a cascade classifier file (" + e.err + "); " + kOpencvDataHint);
  }
  if (cascade == nullptr || cascade->Empty()) {
    params.Fail(key, options.model + ": not a cascade classifier file; " + kOpencvDataHint);
  }
  const cv::Size window = cascade->OriginalWindowSize();
  *geometry = {window, static_cast<double>(window.height)};
  auto search = std::make_shared<CascadeSearch>(std::move(cascade), options);
  return [search](const cv::Mat& image, double max_object_height, std::vector<Detection>* found) {
    search->Run(image, max_object_height, found);
  };
}

const std::vector<std::string>& PeopleBackends() {
  static const std::vector<std::string> backends = {"hog", "dnn"};
  return backends;
}

const std::vector<std::string>& FacesBackends() {
  static const std::vector<std::string> backends = {"cascade", "dnn"};
  return backends;
}

const std::vector<std::string>& ObjectsBackends() {
  static const std::vector<std::string> backends = {"dnn"};
  return backends;
}

const OptionFields<ChannelBackend>& ChannelBackend::PeopleFields() {
  static const OptionFields<ChannelBackend> fields = {
      {"backend", &ChannelBackend::backend,
       "the detector: OpenCV's HOG, or dnn (a network by path; docs/MODELS.md)", &PeopleBackends}};
  return fields;
}

const OptionFields<ChannelBackend>& ChannelBackend::FacesFields() {
  static const OptionFields<ChannelBackend> fields = {
      {"backend", &ChannelBackend::backend,
       "the detector: OpenCV's cascade, or dnn (a network by path; docs/MODELS.md)",
       &FacesBackends}};
  return fields;
}

const OptionFields<ChannelBackend>& ChannelBackend::ObjectsFields() {
  static const OptionFields<ChannelBackend> fields = {
      {"backend", &ChannelBackend::backend, "the detector: a network by path (docs/MODELS.md)",
       &ObjectsBackends}};
  return fields;
}

std::unique_ptr<FeatureMap> CreatePeopleFeature(const ParamBlock& params,
                                                const FeatureSetup& setup) {
  const ObjectChannelOptions channel = ReadChannelOptions(params, ObjectChannelOptions());
  ChannelBackend backend{"hog"};
  ReadFields(params, ChannelBackend::PeopleFields(), &backend);
  if (backend.backend == "dnn") {
    return MakeNetworkChannel(params, setup, channel, DnnDecoder::kYolox, "person",
                              cv::Size(32, 64));
  }
  // The model first: it sets the defaults of the box shares (ForModel).
  HogPeopleOptions hog;
  ReadFields(params, {FieldNamed(HogPeopleOptions::Fields(), "model")}, &hog);
  hog = HogPeopleOptions::ForModel(hog.model);
  ReadFields(params, HogPeopleOptions::Fields(), &hog);
  const std::string error = hog.Check();
  if (!error.empty()) params.FailCheck(error);
  return std::make_unique<ObjectFeature>(std::make_unique<ObjectChannel>(
      channel, HogPeopleGeometry(hog), "person", MakeHogPeopleSearch(hog)));
}

std::unique_ptr<FeatureMap> CreateObjectsFeature(const ParamBlock& params,
                                                 const FeatureSetup& setup) {
  const ObjectChannelOptions channel = ReadChannelOptions(params, ObjectChannelOptions());
  ChannelBackend backend{"dnn"};
  ReadFields(params, ChannelBackend::ObjectsFields(), &backend);
  return MakeNetworkChannel(params, setup, channel, DnnDecoder::kYolox, "", cv::Size(32, 32));
}

ObjectChannelOptions FacesChannelDefaults() {
  ObjectChannelOptions defaults;
  defaults.min_height = 16;
  return defaults;
}

std::unique_ptr<FeatureMap> CreateFacesFeature(const ParamBlock& params,
                                               const FeatureSetup& setup) {
  const ObjectChannelOptions channel = ReadChannelOptions(params, FacesChannelDefaults());
  ChannelBackend backend{"cascade"};
  ReadFields(params, ChannelBackend::FacesFields(), &backend);
  if (backend.backend == "dnn") {
    return MakeNetworkChannel(params, setup, channel, DnnDecoder::kYunet, "face",
                              cv::Size(32, 32));
  }
  FaceCascadeOptions cascade;
  ReadFields(params, FaceCascadeOptions::Fields(), &cascade);
  const std::string model = cascade.model;
  if (model.empty()) params.Fail("model", "must not be empty");
  cascade.model = setup.FindPath(model);
  if (cascade.model.empty()) {
    const std::string places =
        fs::path(model).is_absolute() ? "" : " (looked in " + setup.PlacesSearched() + ")";
    params.Fail("model", "no such file: " + model + places + "; " + kOpencvDataHint);
  }
  const std::string error = cascade.Check();
  if (!error.empty()) params.FailCheck(error);
  DetectorGeometry geometry;
  ObjectSearch search = MakeFaceCascadeSearch(cascade, params, "model", &geometry);
  return std::make_unique<ObjectFeature>(
      std::make_unique<ObjectChannel>(channel, geometry, "face", std::move(search)));
}

}  // namespace attend
