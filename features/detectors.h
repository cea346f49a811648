// The top-down object channels (not in the thesis, whose pre-attentive stage is bottom-up
// only): `people`, OpenCV's HOG pedestrian detector (Dalal and Triggs 2005), and `faces`, a
// cascade classifier (Viola and Jones 2001). Each is an ordinary feature plugin: its map is
// its detections' boxes filled with their confidence, and it reports the detections
// themselves (FeatureMap::detections) for the attention stage to label and seed targets with.
//
// Where the detector looks (`gate`):
//   frame     the whole frame, scaled so that the smallest object asked for (`min_height`)
//             fills the detector's window; every `every` frames, the last detections reused in
//             between;
//   attended  only crops around the frame context's AttentionRegions, each grown by `margin`
//             times its width and height on every side and widened to the window's aspect. An
//             object in a crop is taken to be at most the crop's height and at least the
//             region's height / (1 + 2 margin) (a region is about the object attention looks
//             at; a crop too low for the window of its smallest object is not searched), so
//             each crop is scaled for its smallest object to fill the window and the
//             pyramid stops at the crop's height: a few levels on a small image instead of the
//             whole frame's many. Detections from overlapping crops are merged (non-maximum
//             suppression). Nothing on a sequence's first frame and on still images, which
//             have no regions.
// A frame or a (scaled) crop smaller than the detector's window is not searched.
#pragma once

#include <functional>
#include <memory>
#include <opencv2/core.hpp>
#include <string>
#include <utility>
#include <vector>

#include "features/detection_map.h"
#include "features/feature_map.h"
#include "util/option_fields.h"

namespace attend {

enum class DetectorGate { kAttended, kFrame };


// What both channels share: where the detector looks and how its detections become a map.
struct ObjectChannelOptions {
  DetectorGate gate = DetectorGate::kAttended;
  // A region's crop grows by this times its width on the left and on the right, and times its
  // height above and below.
  double margin = 0.25;
  int every = 1;        // frame gate: search every this many frames, reuse in between
  // attended gate: also search the whole frame every this many frames (a glance at the whole
  // scene, which finds the objects attention has not looked at yet); 0: never.
  int scan_every = 0;
  int min_height = 40;  // smallest object searched for, px of the frame
  int max_height = 0;   // largest object searched for, px of the frame; 0: no bound
  double blur = 0.0;    // sigma of a Gaussian on the map, share of the larger side; 0: none
  DetectionShape shape = DetectionShape::kBox;
  double shape_sigma = 0.5;  // gaussian shape: sigma, share of the box's width and height
  // gaussian shape: the centre's height in the box, a share of it from its top (0.5: the
  // middle; a person's head is near the top of its box).
  double shape_centre_y = 0.5;
  // Each detection's value is its confidence times (its box's height / the map's height) to
  // this power: 0, the confidence alone; below 0, small objects (far faces in a crowd, each
  // looked at about as often as a near one) weigh more per pixel.
  double size_power = 0.0;
  // How its detections are painted (features/detection_map.h).
  DetectionPaint Paint() const;
  // "" when valid; otherwise names the field and the broken constraint.
  std::string Check() const;
  // The fields (util/option_fields.h), which Check and the configuration apply.
  static const OptionFields<ObjectChannelOptions>& Fields();
};

// The HOG pedestrian detector of the `people` channel.
struct HogPeopleOptions {
  std::string model = "default";  // "default": 64x128 (INRIA); "daimler": 48x96
  double hit_threshold = 0.0;     // SVM margin a window needs to count as a hit
  // A detection needs more than this many overlapping hit windows (OpenCV's groupThreshold);
  // 0: every hit window is a detection.
  int min_neighbours = 2;
  double scale = 1.05;  // step between pyramid levels
  int stride = 8;       // window stride, px of the scaled image; a multiple of 8
  // The person inside a detection window: this share of the window's width and of its height,
  // centred. Measured on TUD-Campus and TUD-Stadtmitte (docs/PERFORMANCE.md, "Top-down
  // channels"); the default model's window has a margin of background around the person,
  // Daimler's is about as tall as the person (ForModel).
  double box_width = 0.52;
  double box_height = 0.8;
  std::string Check() const;
  static const OptionFields<HogPeopleOptions>& Fields();
  static const std::vector<std::string>& Models();
  // The defaults with `model` and its box shares.
  static HogPeopleOptions ForModel(const std::string& model);
};

// The default model of `faces`: the frontal-face Haar cascade of Debian's opencv-data.
inline constexpr const char* kDefaultFaceCascade =
    "/usr/share/opencv4/haarcascades/haarcascade_frontalface_default.xml";

// The cascade classifier of the `faces` channel.
struct FaceCascadeOptions {
  // The cascade file; the feature resolves a relative one (FeatureSetup::FindPath).
  std::string model = kDefaultFaceCascade;
  int min_neighbours = 3;  // a detection needs more than this many overlapping hits
  double scale = 1.1;      // step between pyramid levels
  std::string Check() const;
  static const OptionFields<FaceCascadeOptions>& Fields();
};

// What the gate needs to know about a detector: its window, and the height of the object
// filling it (the window's height times the share of it the object takes).
struct DetectorGeometry {
  cv::Size window;
  double object_height = 0.0;
  // A network that takes an image of any size (the dnn backend, features/dnn_detector.h): the
  // whole frame is searched with its longer side at `network_side` px and a crop at that scale
  // times `crop_zoom`, whatever the objects' sizes (boxes shorter than min_height are then
  // dropped), and the pixels counted are the network's (padded to multiples of 32). 0: a
  // sliding-window detector, scaled for its smallest object.
  int network_side = 0;
  double crop_zoom = 1.0;
};

// One search of an image at its own scale and up: the objects found, with their boxes (the
// objects, not the windows) in the image's pixels and confidences in (0, 1]. The image is at
// least the window's size; objects taller than `max_object_height` px (0: any) are not wanted.
using ObjectSearch = std::function<void(const cv::Mat& image, double max_object_height,
                                        std::vector<Detection>* found)>;

// The gate, the `every` schedule and the map around one search function; usable without a
// FrameContext (the tests give it a fake search).
class ObjectChannel {
 public:
  ObjectChannel(const ObjectChannelOptions& options, const DetectorGeometry& geometry,
                std::string label, ObjectSearch search);
  // Forgets the last detections and starts the `every` schedule afresh (a new sequence).
  void Restart();
  // `bgr`: the frame (8-bit); `regions`: where attention looks, in its pixels. Fills `map`
  // (CV_32FC1, the frame's size) and detections().
  void Compute(const cv::Mat& bgr, const std::vector<cv::Rect>& regions, cv::Mat* map);
  const std::vector<Detection>& detections() const { return detections_; }
  // Whether Compute reads `regions` (the attended gate).
  bool reads_regions() const { return options_.gate == DetectorGate::kAttended; }
  // The images the last Compute searched (for tests and benchmarks): how many, and their
  // pixels summed.
  int last_searches() const { return last_searches_; }
  double last_searched_pixels() const { return last_searched_pixels_; }

 private:
  void Search(const cv::Mat& image, const cv::Rect& crop, double min_object, double max_object,
              std::vector<Detection>* found);

  ObjectChannelOptions options_;
  DetectorGeometry geometry_;
  std::string label_;
  ObjectSearch search_;
  int frames_since_search_ = -1;  // -1: no search yet in this sequence
  cv::Size last_size_;
  std::vector<Detection> detections_, scaled_found_;
  std::vector<std::pair<cv::Rect, double>> searched_;  // this frame's crops and smallest objects
  cv::Mat scaled_;
  int last_searches_ = 0;
  double last_searched_pixels_ = 0.0;
};

// The crops the attended gate searches, with the smallest object each is searched for:
// overlapping crops are merged into their bounding box, searched for the smaller of their
// smallest objects, wherever that costs no more than searching both (a search's cost taken as
// its scaled area: the crop's area times (object height / smallest object)^2), until no pair
// merges. Keeps the order of the first crop of each merged group.
std::vector<std::pair<cv::Rect, double>> MergeCrops(std::vector<std::pair<cv::Rect, double>> crops,
                                                    double object_height);

// The crop of `region` the attended gate searches: grown by `margin` times its size on every
// side, widened about its centre to at least `window`'s aspect ratio (never heightened: the
// region's height bounds the object's), clipped to `frame`.
cv::Rect GateCrop(const cv::Rect& region, double margin, cv::Size window, cv::Size frame);

// The HOG people search (OpenCV's HOGDescriptor) and its geometry.
ObjectSearch MakeHogPeopleSearch(const HogPeopleOptions& options);
DetectorGeometry HogPeopleGeometry(const HogPeopleOptions& options);

// The cascade search, from a file: ConfigError at params' `key` when it is missing,
// unreadable or not a cascade, naming the file and the package opencv-data.
ObjectSearch MakeFaceCascadeSearch(const FaceCascadeOptions& options, const ParamBlock& params,
                                   const std::string& key, DetectorGeometry* geometry);

// The detector behind a channel (`backend`): OpenCV's HOG (`people`) or cascade (`faces`), or a
// network (`dnn`, features/dnn_detector.h).
struct ChannelBackend {
  std::string backend;
  static const OptionFields<ChannelBackend>& PeopleFields();
  static const OptionFields<ChannelBackend>& FacesFields();
  static const OptionFields<ChannelBackend>& ObjectsFields();
};

// Parameters: `backend` (hog | dnn), the fields of ObjectChannelOptions (`gate`: attended |
// frame) and, for hog, of HogPeopleOptions (`model`: default | daimler), for dnn of
// DnnDetectorOptions, under their names. Label "person".
std::unique_ptr<FeatureMap> CreatePeopleFeature(const ParamBlock& params,
                                                const FeatureSetup& setup);
// The channel's defaults for faces, which are smaller than people: min_height 16.
ObjectChannelOptions FacesChannelDefaults();

// Parameters: `backend` (cascade | dnn), the fields of ObjectChannelOptions and of
// FaceCascadeOptions or, for dnn, DnnDetectorOptions (decoder yunet by default). Label "face".
std::unique_ptr<FeatureMap> CreateFacesFeature(const ParamBlock& params, const FeatureSetup& setup);

// Any class a network gives (a COCO detector's cars, dogs, bags...): the dnn backend only,
// labelled with the names file's class names. Parameters: the fields of ObjectChannelOptions
// and of DnnDetectorOptions.
std::unique_ptr<FeatureMap> CreateObjectsFeature(const ParamBlock& params,
                                                 const FeatureSetup& setup);

// The `backend` key's default and choices of each channel.
const std::vector<std::string>& PeopleBackends();
const std::vector<std::string>& FacesBackends();
const std::vector<std::string>& ObjectsBackends();

}  // namespace attend
