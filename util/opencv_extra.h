// The OpenCV modules that only some runs need, behind one shared library that attend loads the
// first time one of them is asked for (docs/DESIGN.md, "OpenCV modules loaded on demand").
//
// Debian's imgcodecs, videoio, video, tracking, objdetect and saliency bring in about 250
// libraries (GDAL, GDCM, poppler, ffmpeg, GStreamer, protobuf...) that cost a process about
// 50 MiB of resident memory before its first frame. attend links only OpenCV's core and
// imgproc; the module `libattend_opencv_extra.so` links the rest and hands out the few
// objects attend uses through the interfaces below (only OpenCV and standard types, so the
// module holds nothing of attend's own libraries and no global exists twice).
//
// The module is found next to the running program, in the build tree, then in the install
// tree (ATTEND_OPENCV_EXTRA overrides all three with a file). A process that links these
// modules itself (the Python module) installs its own instance with SetOpenCvExtra.
#pragma once

#include <memory>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace attend::cvextra {

// Bumped whenever a class below changes; the module refuses another version.
inline constexpr int kAbiVersion = 3;

// A video file, a camera or a GStreamer pipeline (cv::VideoCapture).
class Capture {
 public:
  virtual ~Capture() = default;
  virtual bool IsOpened() const = 0;
  virtual bool Grab() = 0;
  // Grabs and decodes the next frame into `image`; false at the end.
  virtual bool Read(cv::Mat* image) = 0;
  // Decodes the frame of the last Grab() into `image` (live pairs grab both views first).
  virtual bool Retrieve(cv::Mat* image) = 0;
  virtual double Get(int property) const = 0;
  virtual bool Set(int property, double value) = 0;
};

// A video file being written (cv::VideoWriter).
class Writer {
 public:
  virtual ~Writer() = default;
  virtual bool IsOpened() const = 0;
  virtual void Write(const cv::Mat& image) = 0;
};

// One of contrib's single-object trackers (cv::Tracker).
class Tracker {
 public:
  virtual ~Tracker() = default;
  virtual void Init(const cv::Mat& image, const cv::Rect& box) = 0;
  virtual bool Update(const cv::Mat& image, cv::Rect* box) = 0;
};

// Dense optical flow between two grey images (cv::DISOpticalFlow).
class DenseFlow {
 public:
  virtual ~DenseFlow() = default;
  virtual void Calc(const cv::Mat& from, const cv::Mat& to, cv::Mat* flow) = 0;
};

// cv::HOGDescriptor with a built-in people detector.
class HogDetector {
 public:
  virtual ~HogDetector() = default;
  virtual cv::Size WindowSize() const = 0;
  // cv::HOGDescriptor::detectMultiScale with `levels` pyramid levels (nlevels).
  virtual void Detect(const cv::Mat& image, int levels, double hit_threshold, cv::Size stride,
                      double scale, double group_threshold, std::vector<cv::Rect>* windows,
                      std::vector<double>* weights) = 0;
};

// cv::CascadeClassifier.
class Cascade {
 public:
  virtual ~Cascade() = default;
  virtual bool Empty() const = 0;
  virtual cv::Size OriginalWindowSize() const = 0;
  // cv::CascadeClassifier::detectMultiScale with levels and weights (outputRejectLevels).
  virtual void Detect(const cv::Mat& grey, double scale, int min_neighbours, cv::Size min_size,
                      cv::Size max_size, std::vector<cv::Rect>* boxes, std::vector<int>* levels,
                      std::vector<double>* weights) = 0;
};

// A network read by cv::dnn (Darknet, ONNX, ...), run on the CPU.
class DnnNet {
 public:
  virtual ~DnnNet() = default;
  // One forward pass on `image` (8-bit or float, 1 or 3 channels, already at the network's
  // input size): cv::dnn::blobFromImage(image, scale, image size, mean, swap_rb), then every
  // unconnected output, in the network's order, into `outputs`.
  virtual void Forward(const cv::Mat& image, double scale, const cv::Scalar& mean, bool swap_rb,
                       std::vector<cv::Mat>* outputs) = 0;
  // The names of the unconnected output layers, in the order Forward fills them.
  virtual const std::vector<std::string>& OutputNames() const = 0;
};

// cv::VideoWriter::fourcc.
constexpr int FourCc(char a, char b, char c, char d) {
  return (a & 255) | ((b & 255) << 8) | ((c & 255) << 16) | ((d & 255) << 24);
}

enum class TrackerType { kKcf, kCsrt };
enum class StaticSaliencyType { kSpectralResidual, kFineGrained };

// What the module offers. cv::Exception thrown by OpenCV passes through unchanged.
class Module {
 public:
  virtual ~Module() = default;
  // imgcodecs: cv::imdecode, cv::imread, cv::imwrite, cv::imencode.
  virtual cv::Mat Decode(const std::vector<uchar>& bytes, int flags) = 0;
  virtual cv::Mat Read(const std::string& path, int flags) = 0;
  virtual bool Write(const std::string& path, const cv::Mat& image,
                     const std::vector<int>& params) = 0;
  virtual bool Encode(const std::string& extension, const cv::Mat& image,
                      const std::vector<int>& params, std::vector<uchar>* bytes) = 0;
  // videoio: a file (or an image-sequence pattern, a pipeline) or a camera, with cv::CAP_*'s
  // backend preference (cv::CAP_ANY = 0); the result may be closed (IsOpened()).
  virtual std::unique_ptr<Capture> OpenCapture(const std::string& source, int api) = 0;
  virtual std::unique_ptr<Capture> OpenCamera(int index, int api) = 0;
  // Whether this OpenCV has the videoio backend `api` (cv::videoio_registry::hasBackend).
  virtual bool HasBackend(int api) = 0;
  virtual std::unique_ptr<Writer> OpenWriter(const std::string& path, int fourcc, double fps,
                                             cv::Size size) = 0;
  // tracking and video.
  virtual std::unique_ptr<Tracker> CreateTracker(TrackerType type, double kcf_detect_thresh) = 0;
  virtual std::unique_ptr<DenseFlow> CreateDisFlow(int preset) = 0;
  // objdetect. LoadCascade throws cv::Exception for a file that is not a cascade.
  virtual std::unique_ptr<HogDetector> CreateHog(bool daimler) = 0;
  virtual std::unique_ptr<Cascade> LoadCascade(const std::string& path) = 0;
  // dnn: cv::dnn::readNet(model, config) (the extension decides the format; `config` may be
  // empty), on the CPU. Throws cv::Exception for a file cv::dnn cannot read.
  virtual std::unique_ptr<DnnNet> ReadNet(const std::string& model, const std::string& config) = 0;
  // saliency: false when the detector fails.
  virtual bool ComputeStaticSaliency(StaticSaliencyType type, const cv::Mat& bgr,
                                     cv::Mat* map) = 0;
};

// The module's one entry point, `attend_opencv_extra`: its instance (owned by the module), or
// null when `abi_version` is not its kAbiVersion.
using EntryPoint = Module* (*)(int abi_version);
inline constexpr const char* kEntryPointName = "attend_opencv_extra";
inline constexpr const char* kLibraryName = "libattend_opencv_extra.so";

// The module, loaded on the first call (thread-safe). Throws InternalError (exit status 1)
// naming `what` (the feature that needs it) and every place looked in when the module is
// missing or of another version.
Module& Get(const std::string& what);

// Whether the module has been loaded (or installed) in this process.
bool Loaded();

// Installs `module` (which the caller keeps alive) instead of loading the file.
void SetOpenCvExtra(Module* module);

}  // namespace attend::cvextra
